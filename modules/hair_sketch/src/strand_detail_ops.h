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

// Draws the strands listed in `affected` toward their guides (chosen among them by the seed).
void clump_strands(const ClumpDetail& d, std::uint32_t seed, const std::vector<int>& affected,
                   std::vector<Polyline>& strands, const DetailContext& context);

}  // namespace lapis::hair_sketch::detail
