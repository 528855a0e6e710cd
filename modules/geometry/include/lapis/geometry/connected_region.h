// The connected region of a vertex: what a "select linked" click takes (Blender's L, Meshmixer's
// double-click), on the whole mesh or only across vertices that share a property, such as the
// label a painted selection gives them.
#pragma once

#include <vector>

#include "lapis/geometry/connectivity.h"

namespace lapis::geometry {

// Vertices (ascending) reachable from `seed` through mesh edges, walking only across vertices
// whose `allowed` entry is non-zero (an empty `allowed` allows every vertex). The seed is
// included when allowed; a seed that is not allowed gives an empty region. Throws
// InvalidArgument for a seed out of range or an `allowed` of a size other than #V.
std::vector<int> connected_region(const Connectivity& conn, int seed, const std::vector<char>& allowed = {});

}  // namespace lapis::geometry
