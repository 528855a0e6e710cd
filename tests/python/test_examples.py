"""The scripts of examples/python run and write what they say."""

import runpy

import meshio
import numpy as np

import lapis
from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples" / "python"


def run(name, *args):
    module = runpy.run_path(str(EXAMPLES / name))
    module["main"](*map(str, args))


def test_deform_head(tmp_path):
    run("deform_head.py", tmp_path / "head.obj")
    V, F = lapis.read_mesh(str(SOURCE_DIR / "assets" / "head.obj"))
    W, F2 = lapis.read_mesh(str(tmp_path / "head.obj"))
    assert np.array_equal(F2, F)
    held = V[:, 1] <= -1.2
    assert np.array_equal(W[held], V[held]) and np.abs(W - V).max() > 0.1


def test_meshio_deform(tmp_path):
    run("meshio_deform.py", tmp_path / "plate.vtk")
    m = meshio.read(tmp_path / "plate.vtk")
    assert abs(m.points[:, 2].max() - 0.4) < 1e-9  # the handle landed


def test_merge_pair(tmp_path):
    run("merge_pair.py", tmp_path)
    for mode in ("independent", "dependent", "transition"):
        V, F = lapis.read_mesh(str(tmp_path / f"dome_on_neck_{mode}.obj"))
        assert lapis.validate(V, F)["ok"]


def test_grow_hairstyle(tmp_path):
    run("grow_hairstyle.py", tmp_path / "style", 300)
    points, offsets = lapis.read_hair(str(tmp_path / "style.hair"))
    assert abs(len(offsets) - 1 - 300) < 30 and points.shape == (offsets[-1], 3)
    assert (tmp_path / "style.obj").stat().st_size > 0
