// How close vertices come to the border of a region: the deform app warns when the border
// of the region of interest passes within a ring or two of a handle, where the fixed region
// beyond it would hold the handle back (a hand painted on its visible side only, whose handle
// then stretches into a tube toward the unpainted back).
#pragma once

#include <vector>

#include "lapis/geometry/connectivity.h"

namespace lapis::geometry {

// The vertices of `candidates` (ascending, each once) within `rings` edges of a vertex
// outside the region, where `inside` flags the region's vertices (#V). rings = 1: the
// candidates with a neighbour outside. Throws InvalidArgument for rings < 1, an `inside` of a
// size other than #V or a candidate out of range.
std::vector<int> near_region_border(const Connectivity& conn, const std::vector<char>& inside,
                                    const std::vector<int>& candidates, int rings);

}  // namespace lapis::geometry
