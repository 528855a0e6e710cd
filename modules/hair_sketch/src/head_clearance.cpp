#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "lapis/hair_sketch/head_clearance.h"

namespace lapis::hair_sketch {
namespace {

// The closest point's distance, negative inside. The side comes from `side` where the caller
// knows it (+1 outside, −1 inside, 0 not known), else from the closest face's normal; where
// the closest point is on an edge or a vertex, where a single face's normal can point the
// wrong way, from the inside test (three ray casts).
double signed_distance(const Head& head, const Eigen::Vector3d& p, const geometry::ClosestPoint& c, int side = 0) {
  bool inside = side < 0;
  if (side == 0) {
    if (c.barycentric.minCoeff() > 1e-6)
      inside = (p - c.point).dot(head.face_normals.row(c.face).transpose()) < 0;
    else
      inside = head.inside(p);
  }
  return inside ? -c.distance : c.distance;
}

double signed_distance(const Head& head, const Eigen::Vector3d& p) {
  return signed_distance(head, p, head.bvh->closest_point(p));
}

// Trilinear interpolation of the 8 corner values at weights w.
double trilinear(const std::array<double, 8>& v, const Eigen::Vector3d& w) {
  double out = 0;
  for (int c = 0; c < 8; ++c)
    out += v[c] * ((c & 1) ? w.x() : 1 - w.x()) * ((c & 2) ? w.y() : 1 - w.y()) * ((c & 4) ? w.z() : 1 - w.z());
  return out;
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
  // Refine the cells the surface may pass through: every point of a cell is within half its
  // diagonal of a corner, so a cell the surface crosses has a corner that close to the surface.
  // (The cells beyond hold no surface; their coarse values keep the right side.)
  block_of_cell_.assign(distance_.size(), -1);
  std::vector<int> refined;
  const double near = std::sqrt(3.0) / 2 * grid.spacing * (1 + 1e-6);  // float-rounded distances
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
  // Neighbouring blocks share their faces' samples: each point of the fine lattice is computed
  // once (a 4×4×4 block has 125 samples, 64 of them its own).
  const std::int64_t fine_x = std::int64_t{kRefinement} * (grid.dims[0] - 1) + 1,
                     fine_y = std::int64_t{kRefinement} * (grid.dims[1] - 1) + 1;
  auto key = [&](int cell, int x, int y, int z) {
    const std::array<int, 3> c = grid.coords(cell);
    return (kRefinement * c[0] + x) +
           fine_x * ((kRefinement * c[1] + y) + fine_y * std::int64_t{kRefinement * c[2] + z});
  };
  std::vector<std::int64_t> keys;
  keys.reserve(refined.size() * kBlockSize);
  for (int cell : refined)
    for (int z = 0; z <= kRefinement; ++z)
      for (int y = 0; y <= kRefinement; ++y)
        for (int x = 0; x <= kRefinement; ++x) keys.push_back(key(cell, x, y, z));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<float> values(keys.size());
  const auto samples = static_cast<std::ptrdiff_t>(keys.size());
#pragma omp parallel for schedule(dynamic, 256)
  for (std::ptrdiff_t u = 0; u < samples; ++u) {
    const std::int64_t k = keys[u];
    const Eigen::Vector3i f(static_cast<int>(k % fine_x), static_cast<int>(k / fine_x % fine_y),
                            static_cast<int>(k / (fine_x * fine_y)));
    values[u] = static_cast<float>(fine_sample(head, f));
  }
  blocks_.resize(refined.size() * kBlockSize);
  const auto cells = static_cast<std::ptrdiff_t>(refined.size());
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t b = 0; b < cells; ++b) {
    int s = 0;
    for (int z = 0; z <= kRefinement; ++z)
      for (int y = 0; y <= kRefinement; ++y)
        for (int x = 0; x <= kRefinement; ++x)
          blocks_[b * kBlockSize + s++] =
              values[std::lower_bound(keys.begin(), keys.end(), key(refined[b], x, y, z)) - keys.begin()];
  }
}

double HeadClearance::fine_sample(const Head& head, const Eigen::Vector3i& fine) const {
  // The cell holding the sample has exact signed distances at its corners, and the distance is
  // 1-Lipschitz: at weights w within the cell the distance is within e = Σ wᵢ |x − cᵢ| of the
  // corners' trilinear value. Where that value is farther than e from zero, it gives the side
  // without the inside test's ray casts.
  std::array<int, 3> c;
  Eigen::Vector3d w;
  for (int a = 0; a < 3; ++a) {
    c[a] = std::min(fine[a] / kRefinement, grid_.dims[a] - 2);
    w[a] = static_cast<double>(fine[a] - kRefinement * c[a]) / kRefinement;
  }
  const Eigen::Vector3d corner = grid_.position(grid_.index(c[0], c[1], c[2]));
  const Eigen::Vector3d p = corner + grid_.spacing * w;
  std::array<double, 8> v;
  double error = 0;
  for (int k = 0; k < 8; ++k) {
    const Eigen::Vector3i o(k & 1, k >> 1 & 1, k >> 2 & 1);
    v[k] = distance_[grid_.index(c[0] + o.x(), c[1] + o.y(), c[2] + o.z())];
    const double weight = (o.x() ? w.x() : 1 - w.x()) * (o.y() ? w.y() : 1 - w.y()) * (o.z() ? w.z() : 1 - w.z());
    error += weight * (p - (corner + grid_.spacing * o.cast<double>())).norm();
  }
  const double value = trilinear(v, w);
  const double margin = error + 1e-6 * grid_.spacing;  // the corners are rounded to float
  const int side = value > margin ? 1 : value < -margin ? -1 : 0;
  return signed_distance(head, p, head.bvh->closest_point(p), side);
}

double HeadClearance::operator()(const Eigen::Vector3f& p) const {
  const Eigen::Vector3f origin = grid_.origin.cast<float>();
  return at_grid((p - origin) / static_cast<float>(grid_.spacing));
}

float HeadClearance::at_grid(const Eigen::Vector3f& q, Eigen::Vector3f* gradient) const {
  const auto& dims = grid_.dims;
  if (gradient) gradient->setZero();
  if (!(q.minCoeff() >= 0 && q.x() <= dims[0] - 1 && q.y() <= dims[1] - 1 && q.z() <= dims[2] - 1))
    return static_cast<float>(grid_.spacing);
  int c[3];
  Eigen::Vector3f w;
  for (int a = 0; a < 3; ++a) {
    c[a] = std::min(static_cast<int>(q[a]), std::max(0, dims[a] - 2));
    w[a] = std::min(q[a] - static_cast<float>(c[a]), 1.0f);
  }
  const int cell = grid_.index(c[0], c[1], c[2]);
  const int block = block_of_cell_[cell];
  float v[8];
  float cells_per_spacing = 1;
  if (block < 0) {
    const int sy = dims[0], sz = dims[0] * dims[1];
    for (int k = 0; k < 8; ++k) v[k] = distance_[cell + (k & 1) + (k >> 1 & 1) * sy + (k >> 2 & 1) * sz];
  } else {
    int s[3];
    for (int a = 0; a < 3; ++a) {
      const float f = w[a] * kRefinement;
      s[a] = std::min(static_cast<int>(f), kRefinement - 1);
      w[a] = f - static_cast<float>(s[a]);
    }
    constexpr int r = kRefinement + 1;
    const float* samples = &blocks_[static_cast<std::size_t>(block) * kBlockSize + s[0] + r * (s[1] + r * s[2])];
    for (int k = 0; k < 8; ++k) v[k] = samples[(k & 1) + r * ((k >> 1 & 1) + r * (k >> 2 & 1))];
    cells_per_spacing = kRefinement;
  }
  // Lerps along x, then y, then z.
  const float x0 = v[0] + w.x() * (v[1] - v[0]), x1 = v[2] + w.x() * (v[3] - v[2]);
  const float x2 = v[4] + w.x() * (v[5] - v[4]), x3 = v[6] + w.x() * (v[7] - v[6]);
  const float y0 = x0 + w.y() * (x1 - x0), y1 = x2 + w.y() * (x3 - x2);
  if (gradient) {  // of the interpolant, per grid spacing
    const float dx0 = v[1] - v[0] + w.y() * (v[3] - v[2] - v[1] + v[0]);
    const float dx1 = v[5] - v[4] + w.y() * (v[7] - v[6] - v[5] + v[4]);
    const float dy0 = x1 - x0, dy1 = x3 - x2;
    *gradient = cells_per_spacing * Eigen::Vector3f(dx0 + w.z() * (dx1 - dx0), dy0 + w.z() * (dy1 - dy0), y1 - y0);
  }
  return y0 + w.z() * (y1 - y0);
}

Eigen::Vector3f HeadClearance::push_out(const Eigen::Vector3f& p, float clearance) const {
  // Newton on the sampled distance at grid coordinates, with the gradient of its trilinear
  // interpolant: one lookup per step.
  const Eigen::Vector3f origin = grid_.origin.cast<float>();
  const float spacing = static_cast<float>(grid_.spacing);
  Eigen::Vector3f q = (p - origin) / spacing, g;
  bool moved = false;
  for (int newton = 0; newton < 5; ++newton) {
    const float d = at_grid(q, &g);  // g: distance per grid spacing
    if (d >= clearance) break;
    const float g2 = g.squaredNorm();
    if (!(g2 > 1e-4f * spacing * spacing)) break;  // a ridge of the distance deep inside: no way out
    q += (clearance - d) / g2 * g;
    moved = true;
  }
  return moved ? Eigen::Vector3f(origin + spacing * q) : p;
}

}  // namespace lapis::hair_sketch
