#include <algorithm>
#include <array>
#include <cmath>

#include "lapis/hair_sketch/strand_detail.h"

namespace lapis::hair_sketch {
namespace {

// Signed distance to the head: the closest point's distance, negative inside. The side comes
// from the closest face's normal; where the closest point is on an edge or a vertex, where a
// single face's normal can point the wrong way, from the inside test.
double signed_distance(const Head& head, const Eigen::Vector3d& p) {
  const geometry::ClosestPoint c = head.bvh->closest_point(p);
  bool inside = false;
  if (c.barycentric.minCoeff() > 1e-6)
    inside = (p - c.point).dot(head.face_normals.row(c.face).transpose()) < 0;
  else
    inside = head.inside(p);
  return inside ? -c.distance : c.distance;
}

// Trilinear interpolation of the 8 corner values at weights w.
double trilinear(const std::array<double, 8>& v, const Eigen::Vector3d& w) {
  double out = 0;
  for (int c = 0; c < 8; ++c)
    out += v[c] * ((c & 1) ? w.x() : 1 - w.x()) * ((c & 2) ? w.y() : 1 - w.y()) * ((c & 4) ? w.z() : 1 - w.z());
  return out;
}

// The cell of grid coordinates q (its lowest node) and the weights within it.
std::array<int, 3> cell_of(const hair_field::Grid& grid, const Eigen::Vector3d& q, Eigen::Vector3d& w) {
  std::array<int, 3> c;
  for (int a = 0; a < 3; ++a) {
    c[a] = std::clamp(static_cast<int>(q[a]), 0, std::max(0, grid.dims[a] - 2));
    w[a] = std::clamp(q[a] - c[a], 0.0, 1.0);
  }
  return c;
}

}  // namespace

HeadClearance::HeadClearance(const Head& head, const hair_field::Grid& grid)
    : grid_(grid), distance_(static_cast<std::size_t>(grid.num_nodes())) {
  const auto n = static_cast<std::ptrdiff_t>(grid.num_nodes());
  // Nodes far outside the head's box only need "far": the closest-point query is the cost.
  const double far = 4 * grid.spacing;
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p = grid.position(static_cast<int>(i));
    const double box_distance = head.box.exteriorDistance(p);
    distance_[i] = static_cast<float>(box_distance > far ? box_distance : signed_distance(head, p));
  }
  // Refine the cells the surface may pass through: a corner within a cell diagonal of it.
  block_of_cell_.assign(distance_.size(), -1);
  std::vector<int> refined;
  const double near = std::sqrt(3.0) * grid.spacing;
  for (int k = 0; k + 1 < grid.dims[2]; ++k)
    for (int j = 0; j + 1 < grid.dims[1]; ++j)
      for (int i = 0; i + 1 < grid.dims[0]; ++i) {
        double closest = 1e300;
        for (int c = 0; c < 8; ++c)
          closest = std::min<double>(closest,
                                     std::abs(distance_[grid.index(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2 & 1))]));
        if (closest > near) continue;
        block_of_cell_[grid.index(i, j, k)] = static_cast<int>(refined.size());
        refined.push_back(grid.index(i, j, k));
      }
  blocks_.resize(refined.size() * kBlockSize);
  const auto cells = static_cast<std::ptrdiff_t>(refined.size());
#pragma omp parallel for schedule(dynamic, 4)
  for (std::ptrdiff_t b = 0; b < cells; ++b) {
    const Eigen::Vector3d corner = grid.position(refined[b]);
    int s = 0;
    for (int z = 0; z <= kRefinement; ++z)
      for (int y = 0; y <= kRefinement; ++y)
        for (int x = 0; x <= kRefinement; ++x)
          blocks_[b * kBlockSize + s++] =
              static_cast<float>(signed_distance(head, corner + grid.spacing / kRefinement * Eigen::Vector3d(x, y, z)));
  }
}

double HeadClearance::coarse(const Eigen::Vector3d& q) const {
  Eigen::Vector3d w;
  const auto c = cell_of(grid_, q, w);
  std::array<double, 8> v;
  for (int k = 0; k < 8; ++k)
    v[k] = distance_[grid_.index(std::min(c[0] + (k & 1), grid_.dims[0] - 1),
                                 std::min(c[1] + (k >> 1 & 1), grid_.dims[1] - 1),
                                 std::min(c[2] + (k >> 2 & 1), grid_.dims[2] - 1))];
  return trilinear(v, w);
}

double HeadClearance::operator()(const Eigen::Vector3f& p) const {
  const Eigen::Vector3d q = grid_.to_grid(p.cast<double>());
  const auto& dims = grid_.dims;
  if (!(q.minCoeff() >= 0 && q.x() <= dims[0] - 1 && q.y() <= dims[1] - 1 && q.z() <= dims[2] - 1))
    return grid_.spacing;  // the grid surrounds the head with a margin: outside it is clear
  Eigen::Vector3d w;
  const auto c = cell_of(grid_, q, w);
  const int block = block_of_cell_[grid_.index(c[0], c[1], c[2])];
  if (block < 0) return coarse(q);
  // The fine sub-cell within the block.
  const Eigen::Vector3d f = w * kRefinement;
  Eigen::Vector3d fw;
  std::array<int, 3> s;
  for (int a = 0; a < 3; ++a) {
    s[a] = std::min(static_cast<int>(f[a]), kRefinement - 1);
    fw[a] = f[a] - s[a];
  }
  const float* samples = &blocks_[static_cast<std::size_t>(block) * kBlockSize];
  std::array<double, 8> v;
  constexpr int r = kRefinement + 1;
  for (int k = 0; k < 8; ++k)
    v[k] = samples[(s[0] + (k & 1)) + r * ((s[1] + (k >> 1 & 1)) + r * (s[2] + (k >> 2 & 1)))];
  return trilinear(v, fw);
}

}  // namespace lapis::hair_sketch
