#include "lapis/geometry/tet_mesh.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/bvh.h"

namespace lapis::geometry {
namespace {

Eigen::Vector3d corner(const TetMesh& m, int t, int k) { return m.V.row(m.T(t, k)).transpose(); }

// Distance from p to tet t (0 inside): the nearest of its four faces when outside.
double distance_to_tet(const TetMesh& m, int t, const Eigen::Vector3d& p) {
  if (tet_barycentric(m, t, p).minCoeff() >= 0) return 0;
  static constexpr int faces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double best = std::numeric_limits<double>::infinity();
  for (const auto& f : faces) {
    const Eigen::Vector3d a = corner(m, t, f[0]), b = corner(m, t, f[1]), c = corner(m, t, f[2]);
    const Eigen::Vector3d w = closest_point_on_triangle(p, a, b, c);
    best = std::min(best, (w[0] * a + w[1] * b + w[2] * c - p).norm());
  }
  return best;
}

}  // namespace

double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

Eigen::Vector4d tet_barycentric(const TetMesh& m, int t, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = corner(m, t, 0);
  Eigen::Matrix3d E;
  E << corner(m, t, 1) - a, corner(m, t, 2) - a, corner(m, t, 3) - a;
  const Eigen::Vector3d l = E.partialPivLu().solve(p - a);
  return Eigen::Vector4d(1 - l.sum(), l[0], l[1], l[2]);
}

std::vector<SharedFace> shared_faces(const TetMesh& m) {
  std::map<std::array<int, 3>, std::array<int, 2>> faces;
  for (int t = 0; t < m.num_tets(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<int, 3> f{};
      for (int k = 0, c = 0; k < 4; ++k)
        if (k != skip) f[static_cast<size_t>(c++)] = m.T(t, k);
      std::sort(f.begin(), f.end());
      auto [it, fresh] = faces.try_emplace(f, std::array<int, 2>{t, -1});
      if (!fresh) it->second[1] = t;
    }
  std::vector<SharedFace> out;
  for (const auto& [f, pair] : faces)
    if (pair[1] >= 0) out.push_back({f, pair});
  return out;
}

void require_valid_tets(const TetMesh& m, const char* context) {
  if (m.num_tets() == 0) throw InvalidArgument(std::string(context) + ": the tetrahedral mesh is empty");
  if (!m.V.allFinite()) throw InvalidArgument(std::string(context) + ": a tet mesh vertex is not finite");
  for (int t = 0; t < m.num_tets(); ++t) {
    for (int k = 0; k < 4; ++k)
      if (m.T(t, k) < 0 || m.T(t, k) >= m.num_vertices())
        throw InvalidArgument(std::string(context) + ": tet " + std::to_string(t) + " has vertex " +
                              std::to_string(m.T(t, k)) + ", expected indices in [0, " +
                              std::to_string(m.num_vertices()) + ")");
    if (!(tet_volume(corner(m, t, 0), corner(m, t, 1), corner(m, t, 2), corner(m, t, 3)) > 0))
      throw InvalidArgument(std::string(context) + ": tet " + std::to_string(t) +
                            " has no positive volume (degenerate or inverted)");
  }
}

TetLocator::TetLocator(const TetMesh& mesh) : mesh_(mesh) {
  require_valid_tets(mesh, "geometry::TetLocator()");
  lo_ = mesh.V.colwise().minCoeff().transpose();
  const Eigen::Vector3d extent = mesh.V.colwise().maxCoeff().transpose() - lo_;
  // About one tet per cell: cell³ · #T ≈ box volume (floored for flat boxes).
  const double volume = std::max(extent.prod(), std::pow(extent.maxCoeff() * 1e-3, 3));
  cell_ = std::cbrt(volume / mesh.num_tets());
  for (int a = 0; a < 3; ++a) dims_[a] = std::clamp(static_cast<int>(extent[a] / cell_) + 1, 1, 256);
  std::vector<std::vector<int>> bucket(static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2]);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    Eigen::Vector3d tlo = corner(mesh, t, 0), thi = tlo;
    for (int k = 1; k < 4; ++k) {
      tlo = tlo.cwiseMin(corner(mesh, t, k));
      thi = thi.cwiseMax(corner(mesh, t, k));
    }
    const auto a = cell_of(tlo), b = cell_of(thi);
    for (int z = a[2]; z <= b[2]; ++z)
      for (int y = a[1]; y <= b[1]; ++y)
        for (int x = a[0]; x <= b[0]; ++x) bucket[(static_cast<size_t>(z) * dims_[1] + y) * dims_[0] + x].push_back(t);
  }
  offsets_.assign(bucket.size() + 1, 0);
  for (size_t c = 0; c < bucket.size(); ++c) offsets_[c + 1] = offsets_[c] + static_cast<int>(bucket[c].size());
  items_.reserve(static_cast<size_t>(offsets_.back()));
  for (const auto& b : bucket) items_.insert(items_.end(), b.begin(), b.end());
}

std::array<int, 3> TetLocator::cell_of(const Eigen::Vector3d& p) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo_[a]) / cell_)), 0, dims_[a] - 1);
  return c;
}

int TetLocator::nearest_tet(const Eigen::Vector3d& p) const {
  int best = 0;
  double best_d = std::numeric_limits<double>::infinity();
  for (int t = 0; t < mesh_.num_tets(); ++t)
    if (const double d = distance_to_tet(mesh_, t, p); d < best_d) {
      best_d = d;
      best = t;
    }
  return best;
}

// Of the candidate tets, the one whose smallest coordinate is largest: on a shared face or
// edge the choice is then fixed by the data, not by rounding.
TetLocation TetLocator::locate(const Eigen::Vector3d& p) const {
  if (!p.allFinite()) throw InvalidArgument("geometry::TetLocator::locate(): the point is not finite");
  const auto c = cell_of(p);
  const size_t cell = (static_cast<size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  TetLocation best;
  double best_min = -std::numeric_limits<double>::infinity();
  for (int k = offsets_[cell]; k < offsets_[cell + 1]; ++k) {
    const Eigen::Vector4d b = tet_barycentric(mesh_, items_[k], p);
    if (b.minCoeff() > best_min) {
      best_min = b.minCoeff();
      best.tet = items_[k];
      best.barycentric = b;
    }
  }
  constexpr double kOnFace = -1e-12;  // rounding of a point on a face
  if (best.tet >= 0 && best_min >= kOnFace) {
    best.inside = true;
    return best;
  }
  best.tet = nearest_tet(p);
  best.barycentric = tet_barycentric(mesh_, best.tet, p);
  best.inside = false;
  return best;
}

}  // namespace lapis::geometry
