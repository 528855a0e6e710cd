// The detail operations behind apply_strand_detail, one per kind, on strands as polylines.
#pragma once

#include <vector>

#include "lapis/hair_sketch/strand_detail.h"
#include "strand_polyline.h"

namespace lapis::hair_sketch::detail {

// `to`, or the point as far toward it from `from` as the clearance allows: an offset may not
// take a point closer to the head than context.min_clearance unless it moves it outward.
Eigen::Vector3f keep_clear(const Eigen::Vector3f& from, const Eigen::Vector3f& to, const DetailContext& context);

// Each returns strand `index`'s new points; `outward` is its root's direction from the centre.
Polyline curl_strand(const CurlDetail& d, std::uint32_t seed, int index, const Polyline& p,
                     const DetailContext& context);
Polyline frizz_strand(const FrizzDetail& d, std::uint32_t seed, int index, const Polyline& p,
                      const DetailContext& context);
Polyline vary_length(const LengthDetail& d, std::uint32_t seed, int index, const Polyline& p);
Polyline cut_strand(const CutDetail& d, const Polyline& p);

// `count` distinct entries of `candidates`, by a partial Fisher–Yates shuffle of the seed.
std::vector<int> choose_guides(const std::vector<int>& candidates, int count, std::uint32_t seed);

// Draws the strands listed in `affected` toward their nearest guide (`guides`: positions in
// `strands`; those of fewer than two points or no length guide nothing).
void clump_strands(const ClumpDetail& d, const std::vector<int>& affected, const std::vector<int>& guides,
                   std::vector<Polyline>& strands, const DetailContext& context);

}  // namespace lapis::hair_sketch::detail
