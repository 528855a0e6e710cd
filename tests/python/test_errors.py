"""lapis.Error and kin as Python exceptions that subclass the natural built-ins, with the C++
message; wrong dtypes and shapes are clear errors naming the argument, not crashes."""

import numpy as np
import pytest

import lapis


def test_hierarchy():
    assert issubclass(lapis.InvalidArgument, lapis.Error) and issubclass(lapis.InvalidArgument, ValueError)
    assert issubclass(lapis.UsageError, lapis.InvalidArgument)
    assert issubclass(lapis.IoError, lapis.Error) and issubclass(lapis.IoError, OSError)
    assert issubclass(lapis.NotPositiveDefinite, ArithmeticError)
    assert issubclass(lapis.SolverFailure, RuntimeError) and issubclass(lapis.ResourceLimit, MemoryError)
    assert issubclass(lapis.Error, Exception) and lapis.Error.__module__ == "lapis"


def test_io_error_keeps_the_cpp_message(tmp_path):
    with pytest.raises(OSError) as e:
        lapis.read_mesh(str(tmp_path / "missing.obj"))
    assert isinstance(e.value, lapis.IoError) and "missing.obj" in str(e.value)
    bad = tmp_path / "bad.off"
    bad.write_text("OFF\n3 1 0\n0 0 0\n1 0 0\n")
    with pytest.raises(lapis.IoError, match="bad.off"):
        lapis.read_mesh(str(bad))
    with pytest.raises(lapis.IoError, match="extension"):
        lapis.read_mesh(str(tmp_path / "mesh.xyz"))


def test_invalid_argument_keeps_the_cpp_message():
    V, F = lapis.make_box_bar(4, 2, 2, 2.0, 1.0, 1.0)
    d = lapis.Deformer(V, F)
    d.set_selection([0, 1, 2], regions=[[V.shape[0] - 1]])  # a handle outside the ROI
    with pytest.raises(ValueError) as e:
        d.precompute()
    assert isinstance(e.value, lapis.InvalidArgument)
    assert str(e.value).startswith("mesh_deform::Deformer::precompute(): ")
    with pytest.raises(lapis.InvalidArgument, match="index"):
        lapis.Connectivity(V, F + V.shape[0])


@pytest.mark.parametrize("V,F,error,message", [
    (np.zeros((4, 3), np.float32), [[0, 1, 2]], TypeError, "V must be float64, not float32"),
    (np.zeros((4, 2)), [[0, 1, 2]], ValueError, r"V must have shape \(n, 3\), not \(4, 2\)"),
    (np.zeros(12), [[0, 1, 2]], ValueError, r"V must have shape \(n, 3\), not \(12,\)"),
    (np.zeros((4, 3)), np.zeros((1, 3)), TypeError, "F must be int32 or int64, not float64"),
    (np.zeros((4, 3)), np.zeros((1, 4), np.int32), ValueError, r"F must have shape \(n, 3\), not \(1, 4\)"),
    (np.zeros((4, 3)), np.array([[0, 1, 2**40]]), ValueError, r"F\[2\] = 1099511627776 does not fit"),
])
def test_wrong_dtype_or_shape_is_a_clear_error(V, F, error, message):
    with pytest.raises(error, match=message):
        lapis.face_areas(V, F)


def test_transform_shapes_are_checked():
    V, F = lapis.make_box_bar(4, 2, 2, 2.0, 1.0, 1.0)
    d = lapis.Deformer(V, F)
    d.set_selection("all", regions=[[0]], points=[])
    d.precompute()
    with pytest.raises(ValueError, match=r"regions must have shape \(#region handles, 4, 4\), not \(1, 3, 3\)"):
        d.deform(np.eye(3)[None])
    with pytest.raises(TypeError, match="regions must be float64, not int64"):
        d.deform(np.eye(4, dtype=np.int64)[None])
    with pytest.raises(lapis.InvalidArgument, match=r"Deformer::deform\(\): 0 region and 0 point transforms, expected 1"):
        d.deform(np.zeros((0, 4, 4)))  # one region handle, no transform
