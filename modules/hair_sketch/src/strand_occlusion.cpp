// Density splatting and axis-aligned optical depths for StrandOcclusion (strand_occlusion.h).
#include "lapis/hair_sketch/strand_occlusion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lapis/core/error.h"

namespace lapis::hair_sketch {
namespace {

void check_options(const StrandOcclusionOptions& o) {
  auto bad = [](const std::string& field, const std::string& why) {
    throw Error("hair_sketch::StrandOcclusion: StrandOcclusionOptions::" + field + " " + why);
  };
  if (!(o.shadow_depth > 0) || !std::isfinite(o.shadow_depth)) bad("shadow_depth", "must be positive and finite");
  if (!(o.cell >= 0) || !std::isfinite(o.cell)) bad("cell", "must be 0 (automatic) or positive");
  if (o.cell == 0 && (o.cells_across < 2 || o.cells_across > 512)) bad("cells_across", "must be in [2, 512]");
  if (!(o.sky_weight >= 0 && o.sky_weight <= 1)) bad("sky_weight", "must be in [0, 1]");
}

// Grid-node samples with trilinear weights: node (i, j, k) sits at origin + h (i, j, k).
struct NodeGrid {
  Eigen::Vector3i dims;
  long index(int i, int j, int k) const { return (static_cast<long>(k) * dims.y() + j) * dims.x() + i; }
  long size() const { return static_cast<long>(dims.x()) * dims.y() * dims.z(); }
};

template <class Visit>
void trilinear(const NodeGrid& g, const Eigen::Vector3f& local, Visit&& visit) {
  const Eigen::Vector3f q = local.cwiseMax(0.0f).cwiseMin((g.dims - Eigen::Vector3i::Ones()).cast<float>());
  int base[3];
  float w[3];
  for (int a = 0; a < 3; ++a) {
    base[a] = std::min(static_cast<int>(q[a]), g.dims[a] - 2);
    w[a] = q[a] - static_cast<float>(base[a]);
  }
  for (int c = 0; c < 8; ++c) {
    const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
    const float weight = (dx ? w[0] : 1 - w[0]) * (dy ? w[1] : 1 - w[1]) * (dz ? w[2] : 1 - w[2]);
    visit(g.index(base[0] + dx, base[1] + dy, base[2] + dz), weight);
  }
}

// Optical depth along +axis or −axis (toward the light) at every node, from a density per node:
// the trapezoidal integral of density from the node to the grid's end, times sigma.
void add_light(const NodeGrid& g, const std::vector<float>& density, int axis, int sign, float sigma_h, float weight,
               std::vector<float>& light) {
  const int n = g.dims[axis];
  const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
#pragma omp parallel for schedule(static)
  for (int v = 0; v < g.dims[v_axis]; ++v)
    for (int u = 0; u < g.dims[u_axis]; ++u) {
      float depth = 0, previous = 0;
      for (int s = 0; s < n; ++s) {
        int c[3];
        c[axis] = sign > 0 ? n - 1 - s : s;
        c[u_axis] = u, c[v_axis] = v;
        const long id = g.index(c[0], c[1], c[2]);
        if (s > 0) depth += 0.5f * (previous + density[static_cast<size_t>(id)]) * sigma_h;
        previous = density[static_cast<size_t>(id)];
        light[static_cast<size_t>(id)] += weight * std::exp(-depth);
      }
    }
}

}  // namespace

StrandOcclusion::StrandOcclusion(const Strands& strands, const StrandOcclusionOptions& options) {
  check_options(options);
  if (strands.points.empty()) return;  // no hair: everything is lit
  Eigen::Vector3f lo = strands.points.front(), hi = lo;
  for (const auto& p : strands.points) {
    if (!p.allFinite()) throw Error("hair_sketch::StrandOcclusion: a strand point is not finite");
    lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  }
  const float extent = std::max((hi - lo).maxCoeff(), 1e-6f);
  const float h =
      options.cell > 0 ? static_cast<float>(options.cell) : extent / static_cast<float>(options.cells_across);
  const Eigen::Vector3f size = hi - lo;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::ceil(size[a] / h) + 3;  // a node of margin on each side
    if (cells > 1024)
      throw Error("hair_sketch::StrandOcclusion: StrandOcclusionOptions::cell is too small for the hair's extent");
    dims_[a] = static_cast<int>(cells);
  }
  origin_ = lo - Eigen::Vector3f::Constant(h);
  inv_cell_ = 1.0f / h;
  const NodeGrid g{dims_};

  // Strand length per volume at the nodes: each segment's length splatted at its midpoint.
  std::vector<float> density(static_cast<size_t>(g.size()), 0.0f);
  for (int s = 0; s < strands.count(); ++s)
    for (int i = strands.offsets[static_cast<size_t>(s)] + 1; i < strands.offsets[static_cast<size_t>(s) + 1]; ++i) {
      const Eigen::Vector3f a = strands.points[static_cast<size_t>(i) - 1], b = strands.points[static_cast<size_t>(i)];
      const float length = (b - a).norm();
      trilinear(g, (0.5f * (a + b) - origin_) * inv_cell_,
                [&](long id, float w) { density[static_cast<size_t>(id)] += w * length; });
    }
  // The density a typical bit of hair sits in: the density-weighted mean, which thin
  // half-empty cells at the hair's surface barely change.
  double sum = 0, sum_sq = 0;
  for (const float d : density) sum += d, sum_sq += static_cast<double>(d) * d;
  light_.assign(density.size(), 0.0f);
  if (sum <= 0) {
    std::fill(light_.begin(), light_.end(), 1.0f);
    return;
  }
  const double mean = sum_sq / sum;  // in length per cell
  const auto sigma_h = static_cast<float>(h / (mean * options.shadow_depth));
  const auto sky = static_cast<float>(options.sky_weight), side = (1.0f - sky) / 4.0f;
  add_light(g, density, 1, +1, sigma_h, sky, light_);
  for (const int axis : {0, 2})
    for (const int sign : {-1, +1}) add_light(g, density, axis, sign, sigma_h, side, light_);
}

float StrandOcclusion::transmittance(const Eigen::Vector3f& p) const {
  if (light_.empty()) return 1.0f;
  const Eigen::Vector3f local = (p - origin_) * inv_cell_;
  for (int a = 0; a < 3; ++a)
    if (!(local[a] >= 0 && local[a] <= static_cast<float>(dims_[a] - 1))) return 1.0f;
  float t = 0;
  trilinear(NodeGrid{dims_}, local, [&](long id, float w) { t += w * light_[static_cast<size_t>(id)]; });
  return std::clamp(t, 0.0f, 1.0f);
}

std::vector<float> StrandOcclusion::transmittance(const Strands& strands) const {
  std::vector<float> out(strands.points.size());
  const long n = static_cast<long>(out.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) out[static_cast<size_t>(i)] = transmittance(strands.points[static_cast<size_t>(i)]);
  return out;
}

}  // namespace lapis::hair_sketch
