// A lighter copy of a hairstyle's strands for interactive display. Growth takes small steps
// (≈ 200 points per strand at the default settings), which export and simulation want but a
// screen does not: a software OpenGL renderer spends about half a microsecond per line
// segment, so 20K full strands (4M segments) take two seconds a frame. Decimating each strand
// and, beyond that, showing an evenly spread subset keeps a frame within the budget.
#pragma once

#include <vector>

#include "lapis/hair_sketch/growth.h"

namespace lapis::hair_app {

struct StrandDisplayOptions {
  int max_segments = 200000;       // total budget (met on average over the strands); 0: no limit
  int max_points_per_strand = 32;  // decimation of each strand (its ends always kept)
};

// The strands to draw. `kept` (optional) receives, per returned strand, the index of the
// strand it comes from, so callers can keep per-strand attributes (colour) stable.
hair_sketch::Strands display_strands(const hair_sketch::Strands& strands, const StrandDisplayOptions& options = {},
                                     std::vector<int>* kept = nullptr);

}  // namespace lapis::hair_app
