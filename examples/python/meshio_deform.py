"""Read a mesh with meshio, deform it with Lapis, write it with meshio: a bump pulled out of
the bundled plate.

    python3 examples/python/meshio_deform.py [OUT.vtk]
"""

import pathlib
import sys

import meshio
import numpy as np

import lapis

ASSETS = pathlib.Path(__file__).resolve().parents[2] / "assets"


def main(out="plate_bump.vtk"):
    mesh = meshio.read(ASSETS / "merge" / "plate.obj")
    V, F = mesh.points, mesh.cells_dict["triangle"]  # float64 and int64 arrays, as meshio gives them
    r = np.linalg.norm(V[:, :2], axis=1)
    d = lapis.Deformer(V, F, method="arap", arap_iterations=5)
    d.set_selection(np.flatnonzero(r < 1.2), regions=[np.flatnonzero(r < 0.3)])
    d.precompute()
    lift = np.eye(4)
    lift[2, 3] = 0.4
    W = d.deform([lift])
    meshio.write(out, meshio.Mesh(W, [("triangle", F)]))
    print(f"{out}: peak {W[:, 2].max():.3f} over a plate of {V.shape[0]} vertices")


if __name__ == "__main__":
    main(*sys.argv[1:])
