#include "lapis/geometry/mirror_vertices.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include "lapis/core/error.h"

namespace lapis::geometry {
namespace {

using Cell = std::array<std::int64_t, 3>;

// Vertices sorted by their grid cell: the cell of a point and its 26 neighbours hold every
// vertex within one cell size of it.
class BucketGrid {
 public:
  BucketGrid(const Vertices& V, double cell) : V_(V), lo_(V.colwise().minCoeff().transpose()) {
    // Cells no finer than the coordinates resolve, so the indices stay far inside int64.
    const double extent = (V.colwise().maxCoeff().transpose() - lo_).maxCoeff();
    cell_ = std::max(cell, 1e-12 * std::max(extent, 1e-300));
    entries_.reserve(static_cast<size_t>(V.rows()));
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      entries_.push_back({cell_of(V.row(v).transpose()), static_cast<int>(v)});
    std::sort(entries_.begin(), entries_.end());
  }

  // The nearest vertex within `radius` (<= the cell size) of p, or -1.
  int nearest(const Eigen::Vector3d& p, double radius) const {
    const Cell c = cell_of(p);
    int best = -1;
    double best_d = radius;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const Cell n{c[0] + dx, c[1] + dy, c[2] + dz};
          auto it = std::lower_bound(entries_.begin(), entries_.end(), Entry{n, -1});
          for (; it != entries_.end() && it->cell == n; ++it) {
            const double d = (V_.row(it->vertex).transpose() - p).norm();
            if (d < best_d || (d == best_d && (best < 0 || it->vertex < best)))  // ties: the lower index
              best = it->vertex, best_d = d;
          }
        }
    return best;
  }

 private:
  struct Entry {
    Cell cell;
    int vertex;
    bool operator<(const Entry& o) const { return cell != o.cell ? cell < o.cell : vertex < o.vertex; }
  };
  Cell cell_of(const Eigen::Vector3d& p) const {
    Cell c;
    for (int k = 0; k < 3; ++k)
      c[static_cast<size_t>(k)] = static_cast<std::int64_t>(std::floor((p[k] - lo_[k]) / cell_));
    return c;
  }

  const Vertices& V_;
  Eigen::Vector3d lo_;
  double cell_ = 1;
  std::vector<Entry> entries_;
};

}  // namespace

MirroredVertices mirror_vertices(const Vertices& V, const std::vector<int>& set, const Eigen::Vector3d& point,
                                 const Eigen::Vector3d& normal, double tolerance) {
  const char* fn = "geometry::mirror_vertices(): ";
  for (int v : set)
    if (v < 0 || v >= V.rows())
      throw InvalidArgument(std::string(fn) + "vertex " + std::to_string(v) + " out of range [0, " +
                            std::to_string(V.rows()) + ")");
  if (!normal.allFinite() || normal.norm() == 0)
    throw InvalidArgument(std::string(fn) + "the plane's normal is zero or not finite");
  if (!point.allFinite()) throw InvalidArgument(std::string(fn) + "the plane's point is not finite");
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw InvalidArgument(std::string(fn) + "tolerance " + std::to_string(tolerance) + ", expected a positive number");
  MirroredVertices out;
  if (set.empty()) return out;
  const Eigen::Vector3d n = normal.normalized();
  const BucketGrid grid(V, tolerance);
  for (int v : set) {
    const Eigen::Vector3d p = V.row(v).transpose();
    const Eigen::Vector3d image = p - 2 * (p - point).dot(n) * n;
    const int match = grid.nearest(image, tolerance);
    (match < 0 ? out.unmatched : out.vertices).push_back(match < 0 ? v : match);
  }
  std::sort(out.vertices.begin(), out.vertices.end());
  out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
  std::sort(out.unmatched.begin(), out.unmatched.end());
  out.unmatched.erase(std::unique(out.unmatched.begin(), out.unmatched.end()), out.unmatched.end());
  return out;
}

}  // namespace lapis::geometry
