#!/usr/bin/python3
"""Flat-shaded PNG of one or more OBJ meshes side by side (docs/images figures; Debian's
python3-matplotlib). Usage: render_mesh.py OUT.png ELEV AZIM MESH.obj [MESH.obj ...]"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def read_obj(path):
    V, F = [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            V.append([float(x) for x in p[1:4]])
        elif p[0] == "f":
            F.append([int(x.split("/")[0]) - 1 for x in p[1:4]])
    return np.array(V), np.array(F)


def main():
    out, elev, azim, paths = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4:]
    fig = plt.figure(figsize=(4 * len(paths), 4.5))
    light = np.array([0.3, -0.5, 0.8]) / np.linalg.norm([0.3, -0.5, 0.8])
    for k, path in enumerate(paths):
        V, F = read_obj(path)
        ax = fig.add_subplot(1, len(paths), k + 1, projection="3d")
        tri = V[F]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
        shade = 0.25 + 0.75 * np.abs(n @ light)
        colors = np.outer(shade, [0.55, 0.7, 0.9])
        ax.add_collection3d(Poly3DCollection(tri, facecolors=colors, edgecolors=(0, 0, 0, 0.15), linewidths=0.1))
        lo, hi = V.min(0), V.max(0)
        c, r = (lo + hi) / 2, (hi - lo).max() / 2
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(c[2] - r, c[2] + r)
        ax.view_init(elev, azim)
        ax.set_axis_off()
        ax.set_title(path.split("/")[-1], fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


main()
