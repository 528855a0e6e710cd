// lapis.geometry in Python: mesh files, validation, connectivity, Laplacians (as CSC arrays that
// the package turns into scipy.sparse matrices), normals and procedural meshes.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>

#include "arrays.h"
#include "bindings.h"
#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"
#include "lapis/geometry/procedural.h"

namespace lapis::python {
namespace {

using namespace lapis::geometry;
using namespace pybind11::literals;

py::tuple mesh_tuple(TriMesh&& mesh) {
  return py::make_tuple(to_numpy(std::move(mesh.V)), to_numpy(std::move(mesh.F)));
}

template <class T>
py::list index_lists(const std::vector<std::vector<T>>& lists) {
  py::list out;
  for (const auto& l : lists) out.append(to_numpy(std::vector<T>(l)));
  return out;
}

py::array pairs(const std::vector<std::array<int, 2>>& p) {
  Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> out(static_cast<Eigen::Index>(p.size()), 2);
  for (size_t i = 0; i < p.size(); ++i) out.row(static_cast<Eigen::Index>(i)) << p[i][0], p[i][1];
  return to_numpy(std::move(out));
}

py::dict validation_dict(const ValidationReport& r) {
  return py::dict("ok"_a = r.ok(), "summary"_a = r.summary(),
                  "out_of_range_faces"_a = to_numpy(std::vector<int>(r.out_of_range_faces)),
                  "non_finite_vertices"_a = to_numpy(std::vector<int>(r.non_finite_vertices)),
                  "degenerate_faces"_a = to_numpy(std::vector<int>(r.degenerate_faces)),
                  "duplicate_faces"_a = to_numpy(std::vector<int>(r.duplicate_faces)),
                  "non_manifold_edges"_a = pairs(r.non_manifold_edges),
                  "non_manifold_vertices"_a = to_numpy(std::vector<int>(r.non_manifold_vertices)),
                  "misoriented_edges"_a = pairs(r.misoriented_edges));
}

py::array span_array(std::span<const int> s) { return to_numpy(std::vector<int>(s.begin(), s.end())); }

MassType mass_type(const std::string& name) {
  if (name == "voronoi" || name == "mixed") return MassType::Voronoi;
  if (name == "barycentric") return MassType::Barycentric;
  throw InvalidArgument("mass type must be voronoi, mixed or barycentric, not '" + name + "'");
}

// The operator functions all take (V, F), build the mesh with the GIL held, then compute
// without it.
// out converts the result to Python (NumPy arrays by default, scipy.sparse for operators).
template <class Result, class Fn, class Out>
auto on_mesh(Fn fn, Out out) {
  return [fn, out](const py::handle& V, const py::handle& F) {
    const TriMesh mesh = to_mesh(V, F);
    Result r;
    {
      py::gil_scoped_release release;
      r = fn(mesh);
    }
    return out(std::move(r));
  };
}

template <class Result, class Fn>
auto on_mesh(Fn fn) {
  return on_mesh<Result>(fn, [](Result r) { return to_numpy(std::move(r)); });
}

void bind_connectivity(py::module_& m) {
  py::class_<Connectivity>(m, "Connectivity", R"(Adjacency of a triangle mesh, built once and queried cheaply.

Connectivity(V, F): V (#V, 3) float64, F (#F, 3) int32/int64. Raises InvalidArgument when a
face index is out of range. Non-manifold edges keep their first two faces.)")
      .def(py::init([](const py::handle& V, const py::handle& F) {
             const TriMesh mesh = to_mesh(V, F);
             py::gil_scoped_release release;
             return new Connectivity(mesh);
           }),
           "V"_a, "F"_a)
      .def_property_readonly("num_vertices", &Connectivity::num_vertices, "#V")
      .def_property_readonly("num_faces", &Connectivity::num_faces, "#F")
      .def_property_readonly("num_edges", &Connectivity::num_edges, "#E, the unique edges")
      .def_property_readonly(
          "edges", [](const Connectivity& c) { return pairs(c.edges()); }, "(#E, 2) int32: edge e joins a < b.")
      .def_property_readonly(
          "edge_faces",
          [](const Connectivity& c) {
            std::vector<std::array<int, 2>> f(static_cast<size_t>(c.num_edges()));
            for (int e = 0; e < c.num_edges(); ++e) f[static_cast<size_t>(e)] = c.edge_faces(e);
            return pairs(f);
          },
          "(#E, 2) int32: the (up to) two faces of each edge, -1 where there is none.")
      .def_property_readonly(
          "face_edges",
          [](const Connectivity& c) {
            Faces fe(c.num_faces(), 3);
            for (int f = 0; f < c.num_faces(); ++f)
              for (int k = 0; k < 3; ++k) fe(f, k) = c.face_edge(f, k);
            return to_numpy(std::move(fe));
          },
          "(#F, 3) int32: edge of face f from corner k to corner (k + 1) % 3.")
      .def_property_readonly(
          "boundary_loops", [](const Connectivity& c) { return index_lists(c.boundary_loops()); },
          "Boundary loops as ordered vertex arrays, surface on the left.")
      .def_property_readonly(
          "is_boundary_vertex",
          [](const Connectivity& c) {
            Eigen::Matrix<bool, Eigen::Dynamic, 1> b(c.num_vertices());
            for (int v = 0; v < c.num_vertices(); ++v) b[v] = c.is_boundary_vertex(v);
            return to_numpy(std::move(b));
          },
          "(#V,) bool.")
      .def("find_edge", &Connectivity::find_edge, "a"_a, "b"_a, "Edge between a and b, or -1.")
      .def(
          "vertex_neighbors", [](const Connectivity& c, int v) { return span_array(c.vertex_neighbors(v)); }, "v"_a,
          "Neighbours of v, ascending.")
      .def(
          "vertex_faces", [](const Connectivity& c, int v) { return span_array(c.vertex_faces(v)); }, "v"_a,
          "Faces around v, ascending.")
      .def(
          "one_ring_ordered", [](const Connectivity& c, int v) { return to_numpy(c.one_ring_ordered(v)); }, "v"_a,
          "Neighbours of v counter-clockwise seen from outside; raises InvalidArgument at a non-manifold vertex.")
      .def("degree", &Connectivity::degree, "v"_a, "Number of neighbours of v.");

  m.def(
      "k_ring",
      [](const Connectivity& c, const py::handle& seeds, int k) {
        return to_numpy(k_ring(c, to_indices(seeds, "seeds"), k));
      },
      "connectivity"_a, "seeds"_a, "k"_a, "Vertices within k edges of any seed, breadth-first (seeds first).");
  m.def(
      "connected_components",
      [](const Connectivity& c) {
        Components r = connected_components(c);
        return py::make_tuple(r.count, to_numpy(std::move(r.face_component)), to_numpy(std::move(r.vertex_component)));
      },
      "connectivity"_a,
      "(count, face_component (#F,), vertex_component (#V,), -1 for isolated vertices) through shared edges.");
  m.def("euler_characteristic", py::overload_cast<const Connectivity&>(&euler_characteristic), "connectivity"_a,
        "V - E + F over the vertices that a face uses.");
  m.def("genus", py::overload_cast<const Connectivity&>(&genus), "connectivity"_a,
        "Sum of the genera of the components (orientable surfaces).");
}

void bind_operators(py::module_& m) {
  // Mesh converted with the GIL held, the operator computed without it.
  auto sparse = [](Sparse (*fn)(const TriMesh&)) {
    return on_mesh<Sparse>(fn, [](Sparse L) { return to_scipy(std::move(L)); });
  };
  m.def("cotan_laplacian", sparse(&cotan_laplacian), "V"_a, "F"_a,
        "#V x #V cotangent Laplacian (scipy.sparse csc), negative semi-definite: L_ij = (cot a + cot b) / 2.");
  m.def("uniform_laplacian", sparse(&uniform_laplacian), "V"_a, "F"_a,
        "#V x #V graph Laplacian (scipy.sparse csc): 1 per edge, -degree on the diagonal.");
  // The same for the operators that take a mass type.
  auto with_mass = [](Sparse (*fn)(const TriMesh&, MassType)) {
    return [fn](const py::handle& V, const py::handle& F, const std::string& type) {
      const TriMesh mesh = to_mesh(V, F);
      const MassType t = mass_type(type);
      Sparse A;
      {
        py::gil_scoped_release release;
        A = fn(mesh, t);
      }
      return to_scipy(std::move(A));
    };
  };
  m.def("mass_matrix", with_mass(&mass_matrix), "V"_a, "F"_a, "type"_a = "voronoi",
        "Diagonal lumped mass matrix (scipy.sparse csc) of vertex_areas().");
  m.def("normalized_cotan_laplacian", with_mass(&normalized_cotan_laplacian), "V"_a, "F"_a, "type"_a = "voronoi",
        "M^-1 L (scipy.sparse csc): rows approximate the Laplace-Beltrami operator; not symmetric.");
  m.def(
      "vertex_areas",
      [](const py::handle& V, const py::handle& F, const std::string& type) {
        const TriMesh mesh = to_mesh(V, F);
        return to_numpy(vertex_areas(mesh, mass_type(type)));
      },
      "V"_a, "F"_a, "type"_a = "voronoi",
      "Per-vertex areas (#V,) float64, 'voronoi' (Meyer et al. mixed) or 'barycentric'; they sum to the area.");
  m.def("laplacian_coordinates",
        on_mesh<Eigen::MatrixX3d>([](const TriMesh& mesh) { return laplacian_coordinates(mesh); }), "V"_a, "F"_a,
        "delta = L V with the cotangent Laplacian: (#V, 3) float64.");
  m.def("face_normals", on_mesh<Vertices>([](const TriMesh& mesh) { return face_normals(mesh); }), "V"_a, "F"_a,
        "Unit face normals (#F, 3) float64.");
  m.def("vertex_normals", on_mesh<Vertices>([](const TriMesh& mesh) { return vertex_normals(mesh); }), "V"_a, "F"_a,
        "Unit vertex normals (#V, 3) float64.");
  m.def("face_areas", on_mesh<Eigen::VectorXd>([](const TriMesh& mesh) { return face_areas(mesh); }), "V"_a, "F"_a,
        "Face areas (#F,) float64.");
}

void bind_procedural(py::module_& m) {
  m.def(
      "make_icosphere", [](int s, double r) { return mesh_tuple(make_icosphere(s, r)); }, "subdivisions"_a,
      "radius"_a = 1.0, "Icosphere (V, F) with 10 * 4**subdivisions + 2 vertices.");
  m.def(
      "make_plane_grid", [](int nx, int ny, double w, double h) { return mesh_tuple(make_plane_grid(nx, ny, w, h)); },
      "nx"_a, "ny"_a, "width"_a = 1.0, "height"_a = 1.0,
      "nx by ny quads split into triangles on [0, width] x [0, height], z = 0: (V, F).");
  m.def(
      "make_box_bar",
      [](int nx, int ny, int nz, double sx, double sy, double sz) {
        return mesh_tuple(make_box_bar(nx, ny, nz, sx, sy, sz));
      },
      "nx"_a, "ny"_a, "nz"_a, "sx"_a, "sy"_a, "sz"_a, "Closed surface of the box [0, sx] x [0, sy] x [0, sz]: (V, F).");
  m.def(
      "make_cylinder", [](int na, int nh, double r, double h) { return mesh_tuple(make_cylinder(na, nh, r, h)); },
      "n_around"_a, "n_height"_a, "radius"_a = 1.0, "height"_a = 1.0, "Open cylinder around z: (V, F).");
  m.def(
      "make_torus", [](int a, int b, double R, double r) { return mesh_tuple(make_torus(a, b, R, r)); }, "n_major"_a,
      "n_minor"_a, "R"_a = 1.0, "r"_a = 0.4, "Torus around z: (V, F).");
  m.def(
      "loop_subdivide",
      [](const py::handle& V, const py::handle& F, int levels) {
        const TriMesh mesh = to_mesh(V, F);
        TriMesh out;
        {
          py::gil_scoped_release release;
          out = loop_subdivide(mesh, levels);
        }
        return mesh_tuple(std::move(out));
      },
      "V"_a, "F"_a, "levels"_a, "Loop subdivision, levels times: (V, F).");
}

}  // namespace

void bind_geometry(py::module_& m) {
  m.def(
      "read_mesh",
      [](const std::filesystem::path& path) {
        TriMesh mesh;
        {
          py::gil_scoped_release release;
          mesh = read_mesh(path);
        }
        return mesh_tuple(std::move(mesh));
      },
      "path"_a,
      R"(Reads OBJ, OFF, PLY or STL (by extension) and returns (V, F): (#V, 3) float64, (#F, 3) int32.

Raises IoError (an OSError) naming the file and the line or byte for a malformed file. The mesh
is checked for index range and finite positions only; see validate().)");
  m.def(
      "write_mesh",
      [](const std::filesystem::path& path, const py::handle& V, const py::handle& F) {
        const TriMesh mesh = to_mesh(V, F);
        py::gil_scoped_release release;
        write_mesh(path, mesh);
      },
      "path"_a, "V"_a, "F"_a,
      "Writes OBJ, OFF, PLY (binary) or STL by extension, atomically; doubles round-trip exactly (not in STL).");
  m.def(
      "validate",
      [](const py::handle& V, const py::handle& F, double degenerate_tolerance, bool check_degenerate,
         bool check_duplicates, bool check_manifold, bool check_orientation) {
        const TriMesh mesh = to_mesh(V, F);
        const ValidationOptions o{degenerate_tolerance, check_degenerate, check_duplicates, check_manifold,
                                  check_orientation};
        ValidationReport r;
        {
          py::gil_scoped_release release;
          r = validate(mesh, o);
        }
        return validation_dict(r);
      },
      "V"_a, "F"_a, "degenerate_tolerance"_a = ValidationOptions{}.degenerate_tolerance, "check_degenerate"_a = true,
      "check_duplicates"_a = true, "check_manifold"_a = true, "check_orientation"_a = true,
      R"(Checks a mesh without raising: a dict with 'ok', 'summary' and the offending indices per kind
(out_of_range_faces, non_finite_vertices, degenerate_faces, duplicate_faces, non_manifold_edges,
non_manifold_vertices, misoriented_edges).)");
  m.def(
      "require_valid",
      [](const py::handle& V, const py::handle& F) { require_valid(to_mesh(V, F), {}, "lapis.require_valid()"); },
      "V"_a, "F"_a, "Raises InvalidArgument with validate()'s summary when the mesh has a problem.");
  bind_connectivity(m);
  bind_operators(m);
  bind_procedural(m);
}

}  // namespace lapis::python
