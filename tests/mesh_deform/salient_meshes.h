// Procedural meshes for the salient-feature tests: a sphere with smooth spikes (Zhao et al.
// Fig. 2) and a bar with a bump.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "lapis/geometry/procedural.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform::test {

// The four tetrahedral directions: spike axes as far apart as four can be.
inline std::vector<Eigen::Vector3d> tetrahedral_directions() {
  return {Eigen::Vector3d(1, 1, 1).normalized(), Eigen::Vector3d(1, -1, -1).normalized(),
          Eigen::Vector3d(-1, 1, -1).normalized(), Eigen::Vector3d(-1, -1, 1).normalized()};
}

// Unit icosphere whose vertices within `radius` radians of each axis are pushed out by
// height (1 − (θ/radius)²)²: smooth spikes with apexes at the axes' directions.
inline geometry::TriMesh spiky_sphere(int subdivisions, const std::vector<Eigen::Vector3d>& axes, double radius = 0.35,
                                      double height = 0.8) {
  geometry::TriMesh m = geometry::make_icosphere(subdivisions, 1.0);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const Eigen::Vector3d p = m.V.row(i).transpose().normalized();
    double r = 1;
    for (const auto& a : axes) {
      const double theta = std::acos(std::clamp(p.dot(a), -1.0, 1.0));
      if (theta < radius) r += height * std::pow(1 - (theta / radius) * (theta / radius), 2);
    }
    m.V.row(i) = r * p.transpose();
  }
  return m;
}

// The vertex nearest the direction a on a mesh around the origin.
inline int apex_vertex(const geometry::TriMesh& m, const Eigen::Vector3d& a) {
  int best = 0;
  for (int i = 1; i < m.num_vertices(); ++i)
    if (m.V.row(i).dot(a) > m.V.row(best).dot(a)) best = i;
  return best;
}

}  // namespace lapis::mesh_deform::test

namespace lapis::mesh_deform::test {

// A box bar [0, 1]² × [0, 4] (n cells across) with a smooth bump of height 0.25 on its x = 1
// side around z = 2, and the bump's vertices as the feature to keep rigid.
struct BumpyBar {
  geometry::TriMesh mesh;
  std::vector<int> bump;  // ascending
};

inline BumpyBar bumpy_bar(int n) {
  BumpyBar b;
  b.mesh = geometry::make_box_bar(n, n, 4 * n, 1.0, 1.0, 4.0);
  for (int i = 0; i < b.mesh.num_vertices(); ++i) {
    const double y = b.mesh.V(i, 1) - 0.5, z = b.mesh.V(i, 2) - 2.0;
    const double r2 = (y * y + z * z) / (0.4 * 0.4);
    if (b.mesh.V(i, 0) > 1 - 1e-9 && r2 < 1) {
      b.mesh.V(i, 0) += 0.25 * (1 - r2) * (1 - r2);
      b.bump.push_back(i);
    }
  }
  return b;
}

}  // namespace lapis::mesh_deform::test
