// Poisson mesh merging (thesis §3.3): deform a source part so its open boundary loops meet
// the target's, keeping its details (implicit Laplacian editing, thesis ch. 2), then zip and
// smooth the seam. Configuration-independent (§3.3.1): the whole source is the ROI and the
// boundary carries position + rotation/scale constraints, so the result does not depend on
// where the source was placed. Configuration-dependent (§3.3.2): the user's placement counts;
// only a band near the boundary deforms, user handles stay fixed, frames are kept.
// Overlapped transition regions (§3.3.3): a band of each mesh next to the seam overlaps the
// other's; both deform, their transformed Laplacian coordinates are tied by E_T and then
// interpolated across the band, instead of smoothing the seam (which filters details).
#pragma once

#include <memory>
#include <vector>

#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

enum class MergeMode {
  Independent,  // §3.3.1
  Dependent,    // §3.3.2
  Transition,   // §3.3.3, configuration-independent (§3.3.1 boundary conditions)
  // §3.4: along the optimal boundary of a band around a feature (BoundaryOptimizer::merge();
  // Merger, which merges given loops, rejects it).
  OptimalBoundary,
};

// Whose transition band the merged surface keeps (§3.3.3 "the connectivity information of one
// transition region"); the other band is removed.
enum class TransitionKeep { Source, Target };

// §3.3.3: "We let the user specify a width for each mesh". No default width fits every mesh,
// so 0 means unset and Transition mode throws until both are given (suggested_transition_width()
// proposes one).
struct TransitionOptions {
  // Band = vertices whose shortest edge path to the merging loop is shorter than the width.
  // Both widths are in the target's units: the source is first scaled so that its merging loops'
  // perimeter equals the target's (what the boundary constraints' s_i do anyway), which keeps the
  // source band independent of how large the source was placed (§3.3.1).
  double source_width = 0;
  double target_width = 0;
  double weight = 0.1;  // w_T of E_T, §3.3.3 ("w_T = 0.1 in our experiments")
  TransitionKeep keep = TransitionKeep::Source;
  // §3.3.3 on §3.3.2's boundary condition: the source stays where the user placed it (its
  // scale too, so the widths are in both meshes' shared units), the boundary frames are kept
  // (R_i = I, positions and s_i change), only source vertices within MergeOptions::roi_width of
  // the loops and the source band move, and MergeOptions::handles stay fixed. false: §3.3.1's
  // (the result does not depend on the source's placement).
  bool configuration_dependent = false;
};

// Eq. 2.11: the merged part's features scale with the boundary (§2.4.4 calls it necessary for
// configuration-independent merging).
inline mesh_deform::ImplicitOptions merge_implicit_defaults() {
  mesh_deform::ImplicitOptions o;
  o.shearing = mesh_deform::ShearingRemoval::ScaleFeatures;
  // The guide bands for rotations accumulated over a drag blend from a fixed region towards
  // the handles; a merge is a one-shot placement with no fixed region, and its boundary
  // rotations carry the source's arbitrary orientation, so guides would make the result
  // depend on the configuration (§3.3.1 requires it not to).
  o.large_rotations = false;
  // The merge is one solve, and §3.3.1 promises a result independent of the source's placement:
  // without the correction, rounding moved the mannequin's head on the man by 2e-5 of the
  // diagonal under a similarity of the head; with it, by 5e-11.
  o.refinement_steps = 1;
  return o;
}

struct MergeOptions {
  MergeMode mode = MergeMode::Independent;
  mesh_deform::ImplicitOptions implicit = merge_implicit_defaults();  // thesis §2.4, Eq. 2.11
  int smooth_iterations = 3;   // §3.3.1 "several iterations of the umbrella operator"; 0: none
  int smooth_rings = 1;        // seam band: strip vertices and this many rings around them
  double smooth_lambda = 0.5;  // umbrella step
  // §2.5 local refinement of a short boundary: below refine_ratio * sqrt(#V) boundary vertices
  // (Independent mode, where the boundary is the whole boundary condition).
  double refine_ratio = 1.0;
  int refine_levels = 2;
  // Dependent mode (§3.3.2): ROI = source vertices within roi_width (edge-path distance) of the
  // source boundary; 0 picks the mean boundary loop diameter (perimeter / π).
  double roi_width = 0;      // also Transition mode with transition.configuration_dependent
  std::vector<int> handles;  // source vertices kept exactly where they are (Dependent mode, and
                             // Transition mode with transition.configuration_dependent)
  // §3.5, Independent mode: source features (vertex lists) that keep their shape. Each shares
  // one deformation gradient implicitly defined over it, so it is "subject to a transformation
  // rather than being completely fixed like in configuration-dependent merging" — the result
  // stays independent of the source's placement. Features may not touch the merging boundary.
  std::vector<std::vector<int>> features;
  // OptimalBoundary mode (BoundaryOptimizer::merge()): Ωf, "the features that the user really
  // wants to paste" (§3.4.1), is held as §3.5 holds a fixed feature: its vertices share one
  // deformation gradient, so it moves by one similarity and only the rest of the part inside
  // the boundary bends. An optimal boundary runs nearer Ωf than ∂Ω0 does, so with plain §2.4
  // editing (false, §3.4.1 as written) less of the band is left to absorb the bend and Ωf
  // itself bends more than along the user's boundary (docs/decisions.md).
  bool hold_feature = true;
  // Transition mode (§3.3.3). Seam smoothing and boundary refinement are not applied in that
  // mode: the transition band replaces the smoothing, which "filters out geometry details".
  TransitionOptions transition;
};

struct MergeTimings {
  double setup_ms = 0;  // correspondence and constraints (+ refinement and deformer precompute in the one-off merge())
  double solve_ms = 0;  // both implicit Laplacian solves and the polar decompositions
  double zip_ms = 0;
  double smooth_ms = 0;  // Transition mode: the band's reconstruction, which replaces the smoothing
  double total_ms = 0;
};

struct MergeResult {
  TriMesh mesh;                 // the merged mesh: target part first, then the source
  std::vector<int> target_map;  // #V_target: merged index, -1 for vertices removed with the band
  std::vector<int>
      source_map;  // #V_source (as given): merged index (-1: removed with the source band, Transition mode)
  // The source the solve ran on (refined; as given + appended vertices). Transition mode: as
  // given, centred and scaled to the target's loop perimeter.
  TriMesh source_rest;
  Vertices source_deformed;          // its positions after the solve, before zipping and smoothing
  std::vector<int> source_boundary;  // source_rest vertices constrained to the target boundary
  std::vector<int> strip_faces;      // merged faces of the re-triangulated gaps
  std::vector<int> seam_vertices;    // merged vertices on the strips
  std::vector<int> smoothed;         // merged vertices the umbrella operator moved (the seam band)
  // Transition mode: the merged vertices of the kept band, and for each the target's share τ of
  // its interpolated Laplacian coordinate (1 where the band meets the kept target, 0 where it
  // meets the rest of the source).
  std::vector<int> transition_vertices;
  std::vector<double> transition_share;
  int refine_levels = 0;
  int roi_vertices = 0;
  mesh_deform::ImplicitReport solver;
  MergeTimings timings;
};

// Precompute once, merge many (thesis §2.5: the factorizations depend only on the source and
// on which vertices are constrained, not on where the constraints put them). The constructor
// refines the source boundary and factorizes the implicit Laplacian system with every source
// boundary vertex as a one-vertex handle; each merge() then costs correspondence, two
// back-substitutions, the polar decompositions, zipping and smoothing — what an interactive
// tool pays when the user moves a key correspondence or picks another target.
// Transition mode (§3.3.3) couples the source with the target's band in one system, so there
// the whole setup runs in merge() and precompute_ms() is 0.
class Merger {
 public:
  // Throws InvalidArgument "mesh_merge::merge(): ..." for options out of range or a handle out
  // of range / on the boundary, transition widths unset (Transition mode), and
  // check_merge_input()'s errors about the source alone (closed, non-manifold).
  explicit Merger(TriMesh source, MergeOptions options = {});
  ~Merger();
  Merger(const Merger&) = delete;
  Merger& operator=(const Merger&) = delete;

  // Throws check_merge_input()'s errors for bad pairs and zip_seams()'s errors; in Transition
  // mode also transition_band()'s errors (a band covering the mesh, not an annulus) and
  // InvalidArgument "mesh_merge::merge(): ..." for bands of two pairs that overlap.
  MergeResult merge(const TriMesh& target, const std::vector<LoopPair>& pairs);

  // Seam smoothing runs after the solve, so changing it needs no new precompute (an app's
  // slider re-merges at merge() cost). Throws InvalidArgument "mesh_merge::merge(): ..." for
  // values out of range, as the constructor does.
  void set_smoothing(int iterations, int rings, double lambda);

  double precompute_ms() const { return precompute_ms_; }
  const MergeOptions& options() const { return options_; }
  const TriMesh& source() const { return source_; }

 private:
  struct Impl;
  TriMesh source_;
  MergeOptions options_;
  std::unique_ptr<Impl> impl_;
  double precompute_ms_ = 0;
};

// A transition width (target units, for both meshes) for Transition mode when the user gave
// none: a fifth of the mean diameter (perimeter / π) of the target loops the pairs name, shrunk
// by factors of 0.75 until the band of every named loop, on the target and on the source (at
// the target's scale), is an annulus transition_band() accepts; where none is, the same after
// separate_loop_neighbourhoods() (refine.h), as the merge then does. Returns 0 for pairs without
// keys. Throws InvalidArgument "mesh_merge::suggested_transition_width(): ..." for a first key
// out of range or off every boundary loop, and, naming the cause, when 20 sizes down to 0.4% of
// the start all fail.
double suggested_transition_width(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs);

// One-off convenience: Merger(source, options).merge(target, pairs), with the precompute time
// counted in timings.setup_ms. Throws what Merger and Merger::merge() throw.
MergeResult merge(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs,
                  const MergeOptions& options = {});

}  // namespace lapis::mesh_merge
