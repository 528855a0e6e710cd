// Loop subdivision (C. Loop, "Smooth subdivision surfaces based on triangles", 1987) with
// the boundary rules of Hoppe et al. 1994 ("Piecewise smooth surface reconstruction").
#include <cmath>
#include <numbers>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/procedural.h"

namespace lapis::geometry {
namespace {

double loop_beta(int n) {
  const double c = 3.0 / 8.0 + 0.25 * std::cos(2 * std::numbers::pi / n);
  return (5.0 / 8.0 - c * c) / n;
}

// Each face (a, b, c) becomes (a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca), where the
// point of edge e is vertex nv + e.
Faces split_faces(const Connectivity& conn, const Faces& F, int nv) {
  const Eigen::Index nf = F.rows();
  Faces out(4 * nf, 3);
#pragma omp parallel for schedule(static)
  for (Eigen::Index f = 0; f < nf; ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    const int i = static_cast<int>(f);
    const int ab = nv + conn.face_edge(i, 0), bc = nv + conn.face_edge(i, 1), ca = nv + conn.face_edge(i, 2);
    out.row(4 * f) << a, ab, ca;
    out.row(4 * f + 1) << b, bc, ab;
    out.row(4 * f + 2) << c, ca, bc;
    out.row(4 * f + 3) << ab, bc, ca;
  }
  return out;
}

TriMesh loop_once(const TriMesh& m) {
  const Connectivity conn(m);
  const int nv = m.num_vertices(), ne = conn.num_edges();
  TriMesh out;
  out.V.resize(nv + ne, 3);
  // Odd (edge) points: 3/8 of the ends + 1/8 of the two opposite corners; midpoint on creases.
#pragma omp parallel for schedule(static)
  for (int e = 0; e < ne; ++e) {
    const auto [a, b] = conn.edges()[e];
    if (conn.edge_face_count(e) != 2) {
      out.V.row(nv + e) = 0.5 * (m.V.row(a) + m.V.row(b));
      continue;
    }
    Eigen::RowVector3d p = 0.375 * (m.V.row(a) + m.V.row(b));
    for (int f : conn.edge_faces(e))
      for (int k = 0; k < 3; ++k)
        if (m.F(f, k) != a && m.F(f, k) != b) p += 0.125 * m.V.row(m.F(f, k));
    out.V.row(nv + e) = p;
  }
  // Even (vertex) points: Loop's beta mask inside, (1/8, 3/4, 1/8) along boundaries/creases.
#pragma omp parallel for schedule(static)
  for (int v = 0; v < nv; ++v) {
    const auto neighbors = conn.vertex_neighbors(v);
    const auto edges = conn.vertex_edges(v);
    Eigen::RowVector3d crease = Eigen::RowVector3d::Zero();
    int crease_count = 0;
    for (size_t i = 0; i < edges.size(); ++i)
      if (conn.edge_face_count(edges[i]) != 2) crease += m.V.row(neighbors[i]), ++crease_count;
    if (crease_count == 2) {
      out.V.row(v) = 0.75 * m.V.row(v) + 0.125 * crease;
    } else if (crease_count > 0 || neighbors.empty()) {
      out.V.row(v) = m.V.row(v);  // corner or isolated: keep
    } else {
      const int n = static_cast<int>(neighbors.size());
      const double beta = loop_beta(n);
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (int w : neighbors) sum += m.V.row(w);
      out.V.row(v) = (1 - n * beta) * m.V.row(v) + beta * sum;
    }
  }
  out.F = split_faces(conn, m.F, nv);
  return out;
}

TriMesh midpoint_once(const TriMesh& m) {
  const Connectivity conn(m);
  TriMesh out;
  out.V.resize(m.num_vertices() + conn.num_edges(), 3);
  out.V.topRows(m.num_vertices()) = m.V;
  for (int e = 0; e < conn.num_edges(); ++e)
    out.V.row(m.num_vertices() + e) = 0.5 * (m.V.row(conn.edges()[e][0]) + m.V.row(conn.edges()[e][1]));
  out.F = split_faces(conn, m.F, m.num_vertices());
  return out;
}

TriMesh repeat(const TriMesh& mesh, int levels, const char* fn, TriMesh (*once)(const TriMesh&)) {
  if (levels < 0) throw InvalidArgument(std::string(fn) + ": levels = " + std::to_string(levels) + ", expected >= 0");
  require_indices_in_range(mesh, fn);
  // Each level quadruples the faces; refuse what int indices cannot address.
  if (static_cast<double>(mesh.num_faces()) * std::pow(4.0, levels) > 2.0e9)
    throw ResourceLimit(std::string(fn) + ": " + std::to_string(levels) + " levels of " +
                        std::to_string(mesh.num_faces()) + " faces exceed 2e9 faces");
  TriMesh m = mesh;
  for (int l = 0; l < levels; ++l) m = once(m);
  return m;
}

}  // namespace

TriMesh loop_subdivide(const TriMesh& mesh, int levels) {
  return repeat(mesh, levels, "geometry::loop_subdivide()", loop_once);
}

TriMesh midpoint_subdivide(const TriMesh& mesh, int levels) {
  return repeat(mesh, levels, "geometry::midpoint_subdivide()", midpoint_once);
}

}  // namespace lapis::geometry
