#include "strand_display.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>

#include "lapis/core/error.h"

namespace lapis::hair_app {
using hair_sketch::Strands;

namespace {

void check(const StrandDisplayOptions& options) {
  if (options.max_segments < 0 || options.max_points_per_strand < 2 || options.stride < 0 || options.current_stride < 0)
    throw InvalidArgument(
        "hair_app::display_strands(): max_segments and the strides must be >= 0 and max_points_per_strand >= 2");
}

// Points a strand of `n` points keeps after decimation: evenly spaced indices, both ends included.
int kept_points(int n, const StrandDisplayOptions& options) { return std::min(n, options.max_points_per_strand); }

}  // namespace

int display_stride(const Strands& strands, const StrandDisplayOptions& options) {
  check(options);
  if (options.stride > 0) return options.stride;
  if (options.max_segments == 0 || strands.segments() <= options.max_segments) return 1;
  long long decimated_segments = 0;
  for (int s = 0; s < strands.count(); ++s)
    decimated_segments += std::max(
        0, kept_points(strands.offsets[static_cast<size_t>(s) + 1] - strands.offsets[static_cast<size_t>(s)], options) -
               1);
  const int best =
      static_cast<int>(std::max(1LL, (decimated_segments + options.max_segments - 1) / options.max_segments));
  return options.current_stride >= 8 && std::abs(options.current_stride - best) <= 1 ? options.current_stride : best;
}

Strands display_strands(const Strands& strands, const StrandDisplayOptions& options, std::vector<int>* kept) {
  check(options);
  const int count = strands.count();
  if (kept) kept->clear();
  if (options.stride == 0 && (options.max_segments == 0 || strands.segments() <= options.max_segments)) {
    if (kept) {
      kept->resize(static_cast<size_t>(count));
      std::iota(kept->begin(), kept->end(), 0);
    }
    return strands;
  }
  // Every stride-th strand, in root order (which spreads them over the scalp), each decimated.
  const int stride = display_stride(strands, options);
  Strands out;
  out.points.reserve(static_cast<size_t>(count / stride + 1) * static_cast<size_t>(options.max_points_per_strand));
  for (int s = 0; s < count; s += stride) {
    const int a = strands.offsets[static_cast<size_t>(s)];
    const int n = strands.offsets[static_cast<size_t>(s) + 1] - a;
    const int m = kept_points(n, options);
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
