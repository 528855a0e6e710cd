// What a user assembles before a merge, as one value (an app's undo history copies it): the two
// meshes, where the source is placed, which boundary loops are paired, the key correspondences
// of each pair, and the options. The edits keep it consistent (a loop is in one pair at most,
// keys follow the source loop's order) so that the module's checks only see real mistakes.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/mesh_merge/merge.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "lapis/mesh_merge/suggest_key.h"

namespace lapis::mesh_merge {

struct PickedPair {
  int source_loop = -1;                 // index into Connectivity(source).boundary_loops()
  int target_loop = -1;                 // index into Connectivity(target).boundary_loops()
  std::vector<KeyCorrespondence> keys;  // in the source loop's order
  bool keys_suggested = false;          // keys is suggest_keys()'s: the user's first key replaces it
};

// The optimal-boundary picks (thesis §3.4) as vertex sets, sorted: a face belongs to a region
// when its three corners do; an empty rough or target region means every face.
struct OptimalPicks {
  std::vector<int> rough, feature;       // Ω0 and Ωf on the source
  std::vector<int> target;               // Ω1 on the target
  std::optional<Placement2D> placement;  // unset: BoundaryOptimizer::suggested_placement()
};

struct MergeSetup {
  // Shared and immutable, so copies of the setup are cheap.
  std::shared_ptr<const TriMesh> source, target;
  Eigen::Matrix4d placement = Eigen::Matrix4d::Identity();  // source rest -> world (a similarity)
  std::vector<PickedPair> pairs;
  MergeOptions options;
  OptimalPicks optimal;  // MergeMode::OptimalBoundary
};

// The picks as BoundaryOptimizer's face lists.
BoundaryRegions boundary_regions(const MergeSetup& setup);

// The source where the user placed it: what merge() gets (Dependent mode keeps this placement).
TriMesh placed_source(const MergeSetup& setup);

// The module's input: one LoopPair per picked pair, keys in order.
std::vector<LoopPair> loop_pairs(const MergeSetup& setup);

// Pairs two loops; a pair already holding either loop is replaced (its keys dropped). Returns
// the new pair's index. Throws InvalidArgument "mesh_merge::pair_loops(): ..." for a negative
// loop index.
int pair_loops(MergeSetup& setup, int source_loop, int target_loop);

// Adds a key to pair `pair`; source_loop is that pair's source loop (its vertex cycle), by which
// the keys are kept in order. A key on the same source or the same target vertex as an existing
// one replaces it; the first key a user adds replaces a suggested one. Throws InvalidArgument "mesh_merge::add_key():
// ..." for a pair out of range or a source vertex not on source_loop.
void add_key(MergeSetup& setup, int pair, KeyCorrespondence key, const std::vector<int>& source_loop);

// Replaces the keys of pair `pair` (every pair when -1) with suggest_key()'s one key for its loops
// as the source is placed, marked suggested; returns the suggestions in the pairs' order.
// source_loops / target_loops are the meshes' boundary loops (Connectivity::boundary_loops()),
// which the pairs index. Throws InvalidArgument "mesh_merge::suggest_keys(): ..." for a pair out
// of range or a loop index past the loops, and suggest_key()'s errors.
std::vector<KeySuggestion> suggest_keys(MergeSetup& setup, const std::vector<std::vector<int>>& source_loops,
                                        const std::vector<std::vector<int>>& target_loops, int pair = -1);

// Adds `vertex` to options.handles, or removes it when it is there already.
void toggle_handle(MergeSetup& setup, int vertex);

// A placement that puts the source next to the target for display: scaled so that source_loop's
// perimeter matches target_loop's, its centroid half a loop radius beyond target_loop's centroid
// (away from the target's centroid), orientation unchanged. Configuration-independent merging
// ignores it; it only keeps parts of very different sizes and places viewable together.
Eigen::Matrix4d suggest_placement(const TriMesh& source, const std::vector<int>& source_loop, const TriMesh& target,
                                  const std::vector<int>& target_loop);

// The target loop a source loop most likely goes onto, for a first placement: the one whose
// side faces the way the source extends from its loop (a head's neck rim faces down, the body's
// neck rim faces up). -1 when target_loops is empty.
int facing_target_loop(const TriMesh& source, const std::vector<int>& source_loop, const TriMesh& target,
                       const std::vector<std::vector<int>>& target_loops);

// suggest_placement() for the source's first loop and its facing_target_loop(). When either
// mesh is closed (no loop to go by): the source scaled to half the target's bounding-box
// diagonal and set beside it along x, a twentieth of that diagonal apart; the identity for an
// empty mesh.
Eigen::Matrix4d suggest_placement(const TriMesh& source, const TriMesh& target);

// Why the setup cannot be merged yet, as a sentence for the UI, or "" when every one of the
// source's `source_loops` loops is paired and every pair has a key (in OptimalBoundary mode:
// when Ωf is painted, and Ω0 unless the source is open). (The module's own checks
// still run on merge: this only spares the user errors for work not done yet.)
std::string missing_input(const MergeSetup& setup, int source_loops);

}  // namespace lapis::mesh_merge
