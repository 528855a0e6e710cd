"""Deformation: every method of the registry, the same result as `lapis deform` for the same
input, keyword options routed to the method's options, distortion metrics."""

import numpy as np
import pytest

import lapis
from conftest import bar_selection, bend, write_handles


def test_every_registry_method_lands_the_handle(bar):
    V, F = bar
    roi, handle = bar_selection(V)
    T = bend(0.3, 0.2)
    assert set(lapis.methods()) >= {"naive", "implicit", "arap", "edge", "salient", "isolines"}
    for method in lapis.methods():
        d = lapis.Deformer(V, F, method=method)
        d.set_selection(roi, regions=[handle])
        d.precompute()
        W = d.deform([T])
        assert W.shape == V.shape and W.dtype == np.float64 and W.flags.c_contiguous
        fixed = np.setdiff1d(np.arange(V.shape[0]), roi)
        assert np.array_equal(W[fixed], V[fixed]), method
        moved = V[handle] @ T[:3, :3].T + T[:3, 3]
        # Hard handles land exactly; the soft ones (salient, isolines) nearly.
        assert np.abs(W[handle] - moved).max() < 0.05, method
        assert d.report()["method"] == d.name == method


@pytest.mark.parametrize("method,options,flags", [
    ("implicit", {}, []),
    ("naive", {"weights": "uniform"}, ["--weights", "uniform"]),
    ("arap", {"arap_iterations": 3}, ["--iterations", "3"]),
    ("edge", {"iterations": 2, "domain": "vertices"}, ["--iterations", "2", "--domain", "vertices"]),
    ("isolines", {"isolines": 8}, ["--isolines", "8"]),
])
def test_equals_the_cli(tmp_path, cli, bar, method, options, flags):
    V, F = bar
    roi, handle = bar_selection(V)
    frames = [[bend(0.2, 0.1)], [bend(0.5, 0.3)]]
    lapis.write_mesh(str(tmp_path / "bar.off"), V, F)
    (tmp_path / "roi.txt").write_text(" ".join(map(str, roi)))
    write_handles(tmp_path / "handles.json", [handle], frames)
    cli("deform", "--mesh", tmp_path / "bar.off", "--roi", tmp_path / "roi.txt", "--handles",
        tmp_path / "handles.json", "--method", method, *flags, "--out", tmp_path / "out.obj")
    expected, _ = lapis.read_mesh(str(tmp_path / "out.obj"))

    d = lapis.Deformer(V, F, method, **options)
    d.set_selection(roi, regions=[handle])
    d.precompute()
    for f in frames:
        W = d.deform(f)
    # The same code on the same input: bit-identical.
    assert np.array_equal(W, expected)


def test_selection_files_drive_the_deformer(tmp_path, bar):
    V, F = bar
    roi, handle = bar_selection(V)
    write_handles(tmp_path / "h.json", [handle], [[bend(0.1, 0.0)]])
    (tmp_path / "roi.txt").write_text(" ".join(map(str, roi)))
    h = lapis.read_handles(str(tmp_path / "h.json"))
    assert np.array_equal(h["regions"][0], handle) and len(h["frames"]) == 1
    assert np.array_equal(lapis.read_roi(str(tmp_path / "roi.txt")), roi)
    regions_T, points_t = h["frames"][0]
    assert regions_T.shape == (1, 4, 4) and points_t.shape == (0, 3)
    assert np.array_equal(regions_T[0], bend(0.1, 0.0))


def test_options_reach_the_method():
    V, F = lapis.make_box_bar(4, 2, 2, 2.0, 1.0, 1.0)
    d = lapis.Deformer(V, F, "edge", iterations=6, domain="vertices", frame="principal")
    assert d.settings.edge.iterations == 6
    assert d.settings.edge.domain == lapis.LaplacianDomain.vertices
    assert d.settings.edge.frame == lapis.ScaleFrame.principal
    s = lapis.method_settings("isolines", fields={"point_handle_radius": 0.05}, fit="similarity")
    assert s.isolines.fields.point_handle_radius == 0.05 and s.isolines.fit == lapis.IsolineFit.similarity
    assert lapis.method_settings("implicit", scale_features=True).scale_features
    with pytest.raises(TypeError, match="unknown option 'iterations' for method 'implicit'"):
        lapis.Deformer(V, F, "implicit", iterations=3)
    with pytest.raises(ValueError, match="method must be one of naive, implicit"):
        lapis.Deformer(V, F, "nonsense")
    with pytest.raises(ValueError, match="edge.domain must be one of edges, vertices"):
        lapis.Deformer(V, F, "edge", domain="faces")
    # The C++ set_options() check, with its message.
    with pytest.raises(lapis.InvalidArgument, match="EdgeLaplacianDeformer::set_options"):
        lapis.Deformer(V, F, "edge", iterations=0)


def test_point_handles_and_dirty_flag(bar):
    V, F = bar
    roi, handle = bar_selection(V)
    d = lapis.Deformer(V, F, "implicit")
    d.set_selection(roi, points=[int(handle[0])])
    assert d.dirty
    W = d.deform(points=[[0.0, 0.3, 0.0]])  # precomputes on demand
    assert not d.dirty
    assert np.allclose(W[handle[0]], V[handle[0]] + [0.0, 0.3, 0.0])


def test_distortion_of_a_rigid_motion_is_zero(bar):
    V, F = bar
    T = bend(0.7, 1.0)
    q = lapis.distortion(V, F, V @ T[:3, :3].T + T[:3, 3])
    assert q["arap_energy"] < 1e-20 and q["edge_length"]["max"] < 1e-12
    q = lapis.distortion(V, F, V * [1.5, 1.0, 1.0])
    assert q["edge_length"]["max"] == pytest.approx(0.5) and q["arap_energy"] > 0.01


def test_transfer_equals_the_cli(tmp_path, cli, bar):
    V, F = bar
    roi, handle = bar_selection(V)
    d = lapis.Deformer(V, F, "implicit")
    d.set_selection(roi, regions=[handle])
    d.precompute()
    pose = d.deform([bend(0.4, 0.2)])
    # The target: the same bar at another resolution, its handles picked by the same rule.
    V2, F2 = lapis.make_box_bar(24, 4, 4, 4.0, 1.0, 1.0)
    roi2, handle2 = bar_selection(V2)
    x = lapis.DeformationTransfer(V, F, V2, F2, {"roi": roi, "regions": [handle]}, {"roi": roi2, "regions": [handle2]})
    W2 = x.transfer(pose)
    assert W2.shape == V2.shape and x.report()["handles"] == 2

    for name, mesh in (("s.off", (V, F)), ("pose.off", (pose, F)), ("t.off", (V2, F2))):
        lapis.write_mesh(str(tmp_path / name), *mesh)
    for name, r in (("roi.txt", roi), ("roi2.txt", roi2)):
        (tmp_path / name).write_text(" ".join(map(str, r)))
    write_handles(tmp_path / "h.json", [handle], [[np.eye(4)]])
    write_handles(tmp_path / "h2.json", [handle2], [[np.eye(4)]])
    cli("transfer", "--source", tmp_path / "s.off", "--source-deformed", tmp_path / "pose.off", "--source-roi",
        tmp_path / "roi.txt", "--source-handles", tmp_path / "h.json", "--target", tmp_path / "t.off",
        "--target-roi", tmp_path / "roi2.txt", "--target-handles", tmp_path / "h2.json", "--out", tmp_path / "out.obj")
    expected, _ = lapis.read_mesh(str(tmp_path / "out.obj"))
    assert np.array_equal(W2, expected)

    # The rest pose transfers to the rest target (up to rounding); unpaired handles are an error.
    assert np.abs(x.transfer(V) - V2).max() < 1e-9
    with pytest.raises(lapis.InvalidArgument, match="do not correspond"):
        lapis.DeformationTransfer(V, F, V2, F2, {"roi": roi, "regions": [handle]},
                                  {"roi": roi2, "regions": [handle2[:4], handle2[4:]]})


def test_salient_features_and_subspace(bar):
    V, F = bar
    roi, handle = bar_selection(V)
    d = lapis.Deformer(V, F, "salient", detect_features=False, subspace_vertices=64)
    middle = np.flatnonzero(np.abs(V[:, 0] - 2.0) < 0.3)
    d.set_features([middle[::-1]])
    d.set_selection(roi, regions=[handle])
    d.precompute()
    assert len(d.features) == 1 and np.array_equal(d.features[0], np.sort(middle))
    assert d.saliency.size == 0  # no detection ran
    TV, T = d.subspace
    assert TV.shape[1] == 3 and T.shape[1] == 4 and T.max() < TV.shape[0]
    # The same tetrahedra given back: the same deformation.
    e = lapis.Deformer(V, F, "salient", detect_features=False, subspace_vertices=64)
    e.set_features([middle])
    e.set_subspace(TV, T)
    e.set_selection(roi, regions=[handle])
    assert np.array_equal(e.deform([bend(0.3, 0.1)]), d.deform([bend(0.3, 0.1)]))
    with pytest.raises(ValueError, match=r"T must have shape \(n, 4\)"):
        e.set_subspace(TV, T[:, :3])


def test_isolines_fields_and_method_members(bar):
    V, F = bar
    roi, handle = bar_selection(V)
    d = lapis.Deformer(V, F, "isolines")
    d.set_selection(roi, regions=[handle])
    d.precompute()
    phi = d.fields
    assert phi.shape == (V.shape[0], 2)
    assert np.abs(phi.sum(axis=1) - 1).max() < 1e-10  # §4.1: the fields partition unity
    assert d.rigidity.shape == (V.shape[0],) and (d.rigidity >= 0).all()
    implicit = lapis.Deformer(V, F, "implicit")
    with pytest.raises(lapis.UsageError, match="only the salient method has it; this deformer's method is 'implicit'"):
        implicit.features
    with pytest.raises(lapis.UsageError, match="only the isolines method"):
        implicit.fields


def test_cold_start_reaches_edge_and_salient():
    """A similarity of both ends of the bar, the ROI all of it: from the handles' rotations and
    scales (the default start) the edge method's first solve is that similarity; from T = I one
    iteration is far from it. The option reaches the salient method too."""
    V, F = lapis.make_box_bar(4, 4, 12, 1.0, 1.0, 3.0)
    ends = [np.flatnonzero(V[:, 2] < 0.3), np.flatnonzero(V[:, 2] > 2.7)]
    T = bend(0.6, 0.3)
    T[:3, :3] *= 1.4
    expected = V @ T[:3, :3].T + T[:3, 3]
    errors = {}
    for start in ("handle_rotations", "identity"):
        d = lapis.Deformer(V, F, "edge", iterations=1, cold_start=start)
        assert d.settings.edge.cold_start == getattr(lapis.ColdStart, start)
        d.set_selection("all", regions=ends)
        errors[start] = np.abs(d.deform([T, T]) - expected).max()
    assert errors["handle_rotations"] < 1e-9
    assert errors["identity"] > 1e-3
    s = lapis.Deformer(V, F, "salient", cold_start="identity", detect_features=False)
    assert s.settings.salient.cold_start == lapis.ColdStart.identity
