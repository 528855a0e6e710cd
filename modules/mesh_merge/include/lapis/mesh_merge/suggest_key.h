// A key correspondence suggested for a pair of boundary loops. Where the key sits decides
// which way round a configuration-independent merge puts the source (upright or face-down),
// so a key placed by eye is easy to get wrong; the suggestion keeps the source the way the
// user sees it placed.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

struct KeySuggestion {
  KeyCorrespondence key;
  // RMS distance between the two normalized loops (centred, unit RMS radius) at the chosen
  // turn, and at the best turn more than a quarter turn away from it. A runner-up close to the
  // residual means nearly round loops, where the placement barely decides the turn.
  double residual = 0;
  double runner_up = 0;
  bool decisive() const { return runner_up > 1.5 * residual; }
};

// Matches the loops as the source is placed (`placement`, a similarity applied to the source:
// MergeSetup::placement). Each loop is resampled at `samples` points (at least two per loop
// vertex, up to 4096) by arc length — the source
// loop forward, the target loop backward, the seam's two sides (boundary.h) — centred and
// scaled to unit RMS radius; the cyclic shift with the least squared distance between the two
// is the match, refined between samples by a parabola (a rotation of the source about its loop
// is what the key decides; its position and size are not). The key is the source loop's vertex farthest along the
// loop's principal direction (its longest axis: a point every rim has), paired with the target loop vertex nearest, by
// arc length, to where the match takes it. Throws InvalidArgument "mesh_merge::suggest_key(): ..." for a loop of fewer
// than 3 vertices, a vertex out of range, a loop of zero length or fewer than 8 samples.
KeySuggestion suggest_key(const TriMesh& source, const Eigen::Matrix4d& placement, const std::vector<int>& source_loop,
                          const TriMesh& target, const std::vector<int>& target_loop, int samples = 256);

}  // namespace lapis::mesh_merge
