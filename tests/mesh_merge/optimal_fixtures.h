// Sources and regions for the optimal-boundary tests (thesis §3.4): a plane with a bump (the
// feature) that is flat out to radius r1 and rippled beyond, and a plane target.
#pragma once

#include <cmath>

#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/optimal_boundary.h"

namespace lapis::mesh_merge::test {

constexpr double kFeatureRadius = 0.3, kFlatRadius = 0.6, kRoughRadius = 0.9;

inline double radius_of(const geometry::TriMesh& m, int v) { return std::hypot(m.V(v, 0), m.V(v, 1)); }

// A 2 x 2 patch centred on the origin: a bump of height 0.25 inside kFeatureRadius, flat to
// kFlatRadius, ripples of amplitude `ripple` beyond.
inline geometry::TriMesh bump_with_ripples(int n = 36, double ripple = 0.04, unsigned seed = 3) {
  geometry::TriMesh m = geometry::make_irregular_grid(n, n, 0.2, seed, 2.0, 2.0);
  for (int v = 0; v < m.num_vertices(); ++v) {
    m.V(v, 0) -= 1, m.V(v, 1) -= 1;
    const double r = radius_of(m, v);
    double z = r < kFeatureRadius ? 0.25 * std::pow(std::cos(0.5 * M_PI * r / kFeatureRadius), 2) : 0;
    if (r > kFlatRadius) z += ripple * std::sin(18 * (r - kFlatRadius));
    m.V(v, 2) = z;
  }
  return m;
}

// Faces whose centroid lies within `radius` of the z axis.
inline std::vector<int> faces_within(const geometry::TriMesh& m, double radius) {
  std::vector<int> faces;
  for (int f = 0; f < m.num_faces(); ++f) {
    Eigen::Vector3d c = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3;
    if (std::hypot(c.x(), c.y()) < radius) faces.push_back(f);
  }
  return faces;
}

inline BoundaryRegions bump_regions(const geometry::TriMesh& source) {
  BoundaryRegions r;
  r.roi_faces = faces_within(source, kRoughRadius);
  r.feature_faces = faces_within(source, kFeatureRadius);
  return r;
}

// A flat 3 x 3 target centred on the origin, tessellated unlike the source.
inline geometry::TriMesh flat_target(int n = 45) {
  geometry::TriMesh t = geometry::make_irregular_grid(n, n, 0.2, 17, 3.0, 3.0);
  t.V.col(0).array() -= 1.5, t.V.col(1).array() -= 1.5;
  return t;
}

}  // namespace lapis::mesh_merge::test
