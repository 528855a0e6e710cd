#include "strand_display.h"

#include <algorithm>
#include <numeric>

#include "lapis/core/error.h"

namespace lapis::hair_app {
using hair_sketch::Strands;

Strands display_strands(const Strands& strands, const StrandDisplayOptions& options, std::vector<int>* kept) {
  if (options.max_segments < 0 || options.max_points_per_strand < 2)
    throw InvalidArgument("hair_app::display_strands(): max_segments must be >= 0 and max_points_per_strand >= 2");
  const int count = strands.count();
  if (kept) kept->clear();
  if (options.max_segments == 0 || strands.segments() <= options.max_segments) {
    if (kept) {
      kept->resize(static_cast<size_t>(count));
      std::iota(kept->begin(), kept->end(), 0);
    }
    return strands;
  }
  // Points each strand keeps after decimation: evenly spaced indices, both ends included.
  auto kept_points = [&](int s) {
    const int n = strands.offsets[static_cast<size_t>(s) + 1] - strands.offsets[static_cast<size_t>(s)];
    return std::min(n, options.max_points_per_strand);
  };
  long long decimated_segments = 0;
  for (int s = 0; s < count; ++s) decimated_segments += std::max(0, kept_points(s) - 1);
  // Then every `stride`-th strand (in root order, which spreads them over the scalp), with a
  // fractional stride so the budget is used fully.
  const double stride = std::max(1.0, static_cast<double>(decimated_segments) / options.max_segments);
  Strands out;
  out.points.reserve(static_cast<size_t>(std::min<long long>(decimated_segments, options.max_segments) +
                                         static_cast<long long>(count / stride) + 1));
  for (double next = 0; next < count; next += stride) {
    const int s = static_cast<int>(next);
    const int a = strands.offsets[static_cast<size_t>(s)];
    const int n = strands.offsets[static_cast<size_t>(s) + 1] - a;
    const int m = kept_points(s);
    if (m == 0) continue;
    for (int k = 0; k < m; ++k) {
      const int i = m == 1 ? 0 : static_cast<int>((static_cast<long long>(k) * (n - 1)) / (m - 1));
      out.points.push_back(strands.points[static_cast<size_t>(a + i)]);
    }
    out.offsets.push_back(static_cast<int>(out.points.size()));
    if (kept) kept->push_back(s);
  }
  return out;
}

}  // namespace lapis::hair_app
