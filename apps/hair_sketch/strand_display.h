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
  // Every stride-th strand is shown, from the first. 0: the smallest stride that meets the
  // budget (display_stride). A whole stride, not a fractional one, so that which strands are
  // shown depends on the stride alone: an app can grow just those first (LiveHairstyle::preview).
  int stride = 0;
  // The stride shown now, kept (with no stride given) while it is within one of the stride
  // that meets the budget, from 8 on: strands a little longer or shorter after an edit then do
  // not change which strands are shown, for at most 1/8 more or fewer segments than the budget.
  int current_stride = 0;
};

// The stride display_strands() picks for `strands`: every stride-th strand, decimated, stays
// within options.max_segments on average (1: every strand is shown).
int display_stride(const hair_sketch::Strands& strands, const StrandDisplayOptions& options = {});

// The strands to draw. `kept` (optional) receives, per returned strand, the index of the
// strand it comes from, so callers can keep per-strand attributes (colour) stable. Strands
// within the budget, with no stride given, are drawn as they are; otherwise each is decimated.
hair_sketch::Strands display_strands(const hair_sketch::Strands& strands, const StrandDisplayOptions& options = {},
                                     std::vector<int>* kept = nullptr);

}  // namespace lapis::hair_app
