// Clumping: strands drawn toward guide strands with a profile along the length.
#include <algorithm>
#include <cmath>
#include <limits>

#include "strand_detail_ops.h"

namespace lapis::hair_sketch::detail {
namespace {

// `count` distinct entries of `affected`, by a partial Fisher–Yates shuffle of the seed.
std::vector<int> choose_guides(const std::vector<int>& affected, int count, std::uint32_t seed) {
  std::vector<int> pool = affected;
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

void clump_strands(const ClumpDetail& d, std::uint32_t seed, const std::vector<int>& affected,
                   std::vector<Polyline>& strands, const DetailContext& context) {
  if (affected.empty()) return;
  const std::vector<int> chosen = choose_guides(affected, d.clumps, seed);
  std::vector<Polyline> guides;
  for (const int g : chosen) guides.push_back(strands[g]);
  std::vector<std::vector<float>> guide_arcs;
  for (const auto& g : guides) guide_arcs.push_back(arc_lengths(g));
  const auto n = static_cast<std::ptrdiff_t>(affected.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    if (std::find(chosen.begin(), chosen.end(), affected[k]) != chosen.end()) continue;  // a guide stays
    Polyline& p = strands[affected[k]];
    const int g = nearest_guide(p.front(), guides);
    const std::vector<float> arc = arc_lengths(p);
    if (!(arc.back() > 0)) continue;
    for (std::size_t i = 1; i < p.size(); ++i) {
      const float t = arc[i] / arc.back();
      const float pull = static_cast<float>(d.strength * std::pow(t, d.profile));
      const Eigen::Vector3f target = point_at(guides[g], guide_arcs[g], t * guide_arcs[g].back());
      p[i] = keep_clear(p[i], p[i] + pull * (target - p[i]), context);
    }
  }
}

}  // namespace lapis::hair_sketch::detail
