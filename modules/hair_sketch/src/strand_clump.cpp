// Clumping: strands drawn toward guide strands with a profile along the length.
#include <algorithm>
#include <cmath>
#include <limits>

#include "strand_detail_ops.h"

namespace lapis::hair_sketch::detail {

std::vector<int> choose_guides(const std::vector<int>& candidates, int count, std::uint32_t seed) {
  std::vector<int> pool = candidates;
  StrandRandom random(seed, -1, 4);
  const int n = static_cast<int>(pool.size());
  count = std::min(count, n);
  for (int k = 0; k < count; ++k) {
    const int j = k + std::min(n - k - 1, static_cast<int>(random.uniform() * (n - k)));
    std::swap(pool[k], pool[j]);
  }
  pool.resize(count);
  return pool;
}

namespace {

int nearest_guide(const Eigen::Vector3f& root, const std::vector<Polyline>& guides) {
  int best = 0;
  float best_d = std::numeric_limits<float>::infinity();
  for (int g = 0; g < static_cast<int>(guides.size()); ++g) {
    const float d = (guides[g].front() - root).squaredNorm();
    if (d < best_d) best_d = d, best = g;
  }
  return best;
}

}  // namespace

void clump_strands(const ClumpDetail& d, const std::vector<int>& affected, const std::vector<int>& guides,
                   std::vector<Polyline>& strands, const DetailContext& context) {
  std::vector<int> chosen;  // the guides with a length to follow
  std::vector<Polyline> shapes;
  std::vector<std::vector<float>> guide_arcs;
  for (const int g : guides) {
    if (strands[g].size() < 2) continue;
    std::vector<float> arc = arc_lengths(strands[g]);
    if (!(arc.back() > 0)) continue;
    chosen.push_back(g);
    shapes.push_back(strands[g]);
    guide_arcs.push_back(std::move(arc));
  }
  if (chosen.empty()) return;
  const auto n = static_cast<std::ptrdiff_t>(affected.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    if (std::find(guides.begin(), guides.end(), affected[k]) != guides.end()) continue;  // a guide stays
    Polyline& p = strands[affected[k]];
    const int g = nearest_guide(p.front(), shapes);
    const std::vector<float> arc = arc_lengths(p);
    if (!(arc.back() > 0)) continue;
    for (std::size_t i = 1; i < p.size(); ++i) {
      const float t = arc[i] / arc.back();
      const float pull = static_cast<float>(d.strength * std::pow(t, d.profile));
      const Eigen::Vector3f target = point_at(shapes[g], guide_arcs[g], t * guide_arcs[g].back());
      p[i] = keep_clear(p[i], p[i] + pull * (target - p[i]), context);
    }
  }
}

}  // namespace lapis::hair_sketch::detail
