"""Meshes: file round trips (Lapis' own readers and meshio), validation, connectivity against
`lapis mesh`, Laplacians as scipy.sparse matrices."""

import json

import meshio
import numpy as np
import pytest
import scipy.sparse

import lapis


@pytest.mark.parametrize("ext", ["obj", "off", "ply"])
def test_round_trip_is_exact(tmp_path, ext):
    V, F = lapis.make_icosphere(2)
    V = V * np.pi  # digits that only a shortest round-trip writer keeps
    lapis.write_mesh(tmp_path / f"m.{ext}", V, F)
    V2, F2 = lapis.read_mesh(str(tmp_path / f"m.{ext}"))
    assert V2.dtype == np.float64 and V2.shape == V.shape
    assert F2.dtype == np.int32 and F2.shape == F.shape
    assert np.array_equal(V2, V) and np.array_equal(F2, F)


def test_meshio_round_trip(tmp_path):
    V, F = lapis.make_torus(24, 12)
    meshio.write(tmp_path / "t.off", meshio.Mesh(V, [("triangle", F)]))
    V2, F2 = lapis.read_mesh(str(tmp_path / "t.off"))
    assert np.allclose(V2, V, rtol=0, atol=1e-15) and np.array_equal(F2, F)
    lapis.write_mesh(str(tmp_path / "t.obj"), V, F)
    m = meshio.read(tmp_path / "t.obj")
    assert np.array_equal(m.points, V) and np.array_equal(m.cells_dict["triangle"], F)


def test_int64_faces_and_views_are_accepted():
    V, F = lapis.make_icosphere(1)
    a = lapis.face_areas(V, F)
    assert np.array_equal(lapis.face_areas(V, F.astype(np.int64)), a)
    big = np.zeros((V.shape[0], 6))
    big[:, ::2] = V  # a strided view: copied, same values
    assert np.array_equal(lapis.face_areas(big[:, ::2], F), a)


def test_connectivity_matches_the_cli(tmp_path, cli):
    V, F = lapis.make_cylinder(20, 6)
    lapis.write_mesh(str(tmp_path / "c.off"), V, F)
    cli("mesh", "--in", tmp_path / "c.off", "--report", tmp_path / "r.json")
    report = json.loads((tmp_path / "r.json").read_text())
    c = lapis.Connectivity(V, F)
    assert report["valid"] and lapis.validate(V, F)["ok"]
    assert c.num_edges == report["edges"]
    assert lapis.connected_components(c)[0] == report["components"]
    assert len(c.boundary_loops) == report["boundary_loops"] == 2
    assert lapis.euler_characteristic(c) == report["euler_characteristic"] == 0
    assert lapis.genus(c) == report["genus"] == 0


def test_connectivity_queries():
    V, F = lapis.make_plane_grid(3, 3)
    c = lapis.Connectivity(V, F)
    assert c.edges.shape == (c.num_edges, 2) and np.all(c.edges[:, 0] < c.edges[:, 1])
    centre = 5  # vertex (1, 1) of the 4 x 4 grid
    ring = c.one_ring_ordered(centre)
    assert sorted(ring) == list(c.vertex_neighbors(centre))
    assert not c.is_boundary_vertex[centre] and c.is_boundary_vertex[0]
    assert list(lapis.k_ring(c, [0], 0)) == [0]
    loop = c.boundary_loops[0]
    assert len(loop) == 12 and c.find_edge(loop[0], loop[1]) >= 0


def test_validate_names_the_offending_faces():
    V, F = lapis.make_icosphere(1)
    F = np.vstack([F, F[:1]])  # a duplicate face
    r = lapis.validate(V, F)
    assert not r["ok"] and list(r["duplicate_faces"]) == [F.shape[0] - 1]
    with pytest.raises(lapis.InvalidArgument, match="duplicate"):
        lapis.require_valid(V, F)


def test_laplacians_are_scipy_sparse():
    V, F = lapis.make_icosphere(2)
    L = lapis.cotan_laplacian(V, F)
    assert scipy.sparse.issparse(L) and L.shape == (V.shape[0],) * 2
    assert abs(L - L.T).max() < 1e-12
    assert np.abs(L @ np.ones(V.shape[0])).max() < 1e-12
    M = lapis.mass_matrix(V, F)
    assert np.allclose(M.diagonal(), lapis.vertex_areas(V, F))
    assert np.isclose(M.diagonal().sum(), lapis.face_areas(V, F).sum())
    # The same operator as laplacian_coordinates uses.
    assert np.allclose(L @ V, lapis.laplacian_coordinates(V, F), atol=1e-14)
    U = lapis.uniform_laplacian(V, F)
    c = lapis.Connectivity(V, F)
    assert np.array_equal(-U.diagonal(), [c.degree(v) for v in range(V.shape[0])])
