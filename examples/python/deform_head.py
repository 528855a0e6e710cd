"""Deform a bundled mesh and write it: the head nods, its neck stays where it is.

    python3 examples/python/deform_head.py [OUT.obj]
"""

import pathlib
import sys

import numpy as np

import lapis

ASSETS = pathlib.Path(__file__).resolve().parents[2] / "assets"


def nod(angle):
    """A turn about the x axis through the head's centre, as a 4x4 transform."""
    c, s = np.cos(angle), np.sin(angle)
    T = np.eye(4)
    T[1:3, 1:3] = [[c, -s], [s, c]]
    return T


def main(out="head_nod.obj"):
    V, F = lapis.read_mesh(str(ASSETS / "head.obj"))
    roi = np.flatnonzero(V[:, 1] > -1.2)  # below it, the neck is held
    crown = np.flatnonzero(V[:, 1] > 0.6)  # grabbed and turned
    d = lapis.Deformer(V, F, method="implicit")
    d.set_selection(roi, regions=[crown])
    d.precompute()
    for k in range(1, 5):  # a drag in four frames: the method follows the rotation
        W = d.deform([nod(0.1 * k)])
    lapis.write_mesh(out, W, F)
    q = lapis.distortion(V, F, W)
    print(f"{out}: {V.shape[0]} vertices, edge length change p95 {q['edge_length']['p95']:.4f}")


if __name__ == "__main__":
    main(*sys.argv[1:])
