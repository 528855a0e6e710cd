// Sources, targets and pairs shared by the mesh_merge tests: procedural parts with a little
// noise (no exact ties for the zipper's greedy choices), and key vertices picked by position.
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include <doctest/doctest.h>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/cut.h"
#include "lapis/mesh_merge/merge.h"
#include "lapis/mesh_merge/metrics.h"

namespace lapis::mesh_merge::test {

using geometry::TriMesh;

inline void jitter(TriMesh& m, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (int v = 0; v < m.num_vertices(); ++v)
    for (int a = 0; a < 3; ++a) m.V(v, a) += u(rng);
}

// The boundary loop vertex of `mesh` whose loop contains a vertex with z near `z` and that
// maximizes x (a key vertex users would click on the same side of both parts).
inline int loop_vertex_max_x(const TriMesh& mesh, double z) {
  const geometry::Connectivity conn(mesh);
  int best = -1;
  double best_dz = 1e300;
  for (const auto& loop : conn.boundary_loops()) {
    double zm = 0;
    for (int v : loop) zm += mesh.V(v, 2);
    zm /= double(loop.size());
    if (std::abs(zm - z) >= best_dz) continue;
    best_dz = std::abs(zm - z);
    best = *std::max_element(loop.begin(), loop.end(), [&](int a, int b) { return mesh.V(a, 0) < mesh.V(b, 0); });
  }
  return best;
}

// A bumpy dome: the upper part of a noisy icosphere, boundary near z = 0.2 (one loop).
inline TriMesh dome(int subdivisions = 3, unsigned seed = 7) {
  TriMesh s = geometry::make_icosphere(subdivisions, 1.0);
  jitter(s, 0.01, seed);
  return cut_by_plane(s, {0, 0, 0.2}, {0, 0, 1}).above;
}

// An open noisy cylinder of radius 1 from z = 0 to 2 (two loops): the body the dome goes on.
inline TriMesh body(int around = 40, int along = 20) {
  TriMesh c = geometry::make_cylinder(around, along, 1.0, 2.0);
  jitter(c, 0.004, 11);
  return c;
}

inline std::vector<LoopPair> dome_on_body(const TriMesh& src, const TriMesh& tgt) {
  return {LoopPair{{KeyCorrespondence{loop_vertex_max_x(src, 0.2), loop_vertex_max_x(tgt, 2.0)}}}};
}

// Two loops: a tube (radius 0.5, z in [0, 1]) between the two halves of a cylinder cut open
// in the middle (radius 1, z in [0, 1] and [2, 3]).
inline TriMesh tube() {
  TriMesh c = geometry::make_cylinder(24, 12, 0.5, 1.0);
  jitter(c, 0.003, 5);
  return c;
}

inline TriMesh split_column() {
  TriMesh c = geometry::make_cylinder(36, 30, 1.0, 3.0);
  jitter(c, 0.003, 9);
  std::vector<int> middle;
  for (int f = 0; f < c.num_faces(); ++f) {
    const double z = (c.V(c.F(f, 0), 2) + c.V(c.F(f, 1), 2) + c.V(c.F(f, 2), 2)) / 3;
    if (z > 1 && z < 2) middle.push_back(f);
  }
  return geometry::remove_faces(c, middle);
}

inline std::vector<LoopPair> tube_in_column(const TriMesh& src, const TriMesh& tgt) {
  return {LoopPair{{KeyCorrespondence{loop_vertex_max_x(src, 0.0), loop_vertex_max_x(tgt, 1.0)}}},
          LoopPair{{KeyCorrespondence{loop_vertex_max_x(src, 1.0), loop_vertex_max_x(tgt, 2.0)}}}};
}

// Seam watertight, the whole merged mesh manifold with no degenerate face, strips not slivers.
inline void require_watertight(const TriMesh& target, const MergeResult& r) {
  const SeamQuality q = seam_quality(target, r);
  CHECK(q.seam_boundary_edges == 0);
  CHECK(q.non_manifold_edges == 0);
  CHECK(q.non_manifold_vertices == 0);
  CHECK(q.degenerate_faces == 0);
  CHECK(q.valid());
  CHECK(q.min_strip_angle_deg > 5.0);
  CHECK(geometry::validate(r.mesh).ok());
}

inline std::filesystem::path external(const std::string& name) {
  return std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "external" / (name + ".off");
}

}  // namespace lapis::mesh_merge::test
