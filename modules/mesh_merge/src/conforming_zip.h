// The seam of one loop pair zipped without removing target faces, for a target whose band next
// to the loop is not an annulus (zip_seams() falls back to it there).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge::detail {

struct ConformingSeam {
  std::vector<int> strip_faces;              // faces replaced or added on both sides of the seam
  std::vector<int> seam_vertices;            // the merged loop (target vertices and inserted source vertices)
  std::vector<std::pair<int, int>> snapped;  // (source vertex, target vertex it became)
};

// A key for the directed edge a → b.
inline std::uint64_t directed_edge(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

// Points nearer a target vertex than this fraction of the edge would leave slivers if inserted.
inline constexpr double kSnapFraction = 0.2;

// A source loop point within kSnapFraction of a target edge's length from one of the edge's
// ends becomes that target vertex (at most one point per vertex, the nearest); every other
// point is inserted into the target edge it lies on and every target loop vertex left alone
// into the source edge spanning it, and the faces on those edges are re-triangulated
// (triangulate_polygon). mesh: the merged mesh, target part then source; target_loop and
// source_loop in its indices; the source loop points lie on the target loop where pair says
// (target_edge, target_t). Faces elsewhere keep their corners: the caller redirects snapped
// source vertices in every face and drops them.
ConformingSeam zip_conforming(TriMesh& mesh, const std::vector<int>& target_loop, const std::vector<int>& source_loop,
                              const BoundaryCorrespondence& pair);

}  // namespace lapis::mesh_merge::detail
