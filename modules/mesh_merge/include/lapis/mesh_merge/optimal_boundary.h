// The optimal merging boundary (thesis §3.4): on the source, the user marks a rough region Ω0
// around the feature region Ωf to be merged, and on the target a region Ω1 without complex
// features. Of the closed edge paths ∂Ω in the band B = Ω0 \ Ωf, the one whose edges change least
// when mapped onto their images on Ω1, up to one similarity T, minimizes Eq. 3.1,
//   E(∂Ω, T) = Σ_{e ∈ ∂Ω} ‖T e − e*‖ · length(e),
// and merging along it (§3.3 with ∂Ω moved to its image) distorts the feature least. The images
// come from the least squares conformal maps of B with Ωf's hole filled (least total area) and of
// Ω1, related by the user's rough 2D placement (§3.4.2). The iteration (§3.4.3) alternates a
// similarity fit with the exact cheapest closed path through the band, found by Dijkstra from
// each vertex of a cut across the band to its twin on the cut's other side.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/polar.h"
#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_merge/merge.h"

namespace lapis::geometry {
class Connectivity;
}

namespace lapis::mesh_merge {

using geometry::Faces;
using geometry::TriMesh;
using geometry::Vertices;

// Face lists; duplicates are ignored.
struct BoundaryRegions {
  std::vector<int> roi_faces;      // Ω0 on the source, containing the feature; empty: every source face
  std::vector<int> feature_faces;  // Ωf ⊂ Ω0: kept as it is, connected, one boundary loop, any genus
  std::vector<int> target_faces;   // Ω1 on the target, a disk; empty: every target face
};

// The 2D similarity from the source band's normalized parameterization (the two farthest points
// of ∂Ω0 at (0, 0) and (1, 0)) to Ω1's (in target length units): the user's rough translate /
// rotate / scale of §3.4.2, which the optimization only fine-tunes.
struct Placement2D {
  double scale = 1;
  double angle = 0;  // radians, counter-clockwise
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& uv) const;
};

struct OptimalBoundaryOptions {
  // §3.4.3 stops when "the change of energy converges or a prescribed maximum number of iterations
  // is reached"; the thesis gives neither value.
  int max_iterations = 30;
  double relative_tolerance = 1e-6;  // stop when |E_k − E_k−1| <= this · E_k
  int max_exact_fill = 1000;         // ∂Ωf corners above which the fill is a centroid fan (O(k³) program)
  bool prune = true;                 // stop each Dijkstra beyond the cheapest loop found so far (exact)
  // The boundary keeps at least this many edges from ∂Ωf: its vertices lie this many edge steps
  // or more from Ωf. §3.4.1 keeps ∂Ω "within the region Ω0 \ Ωfeature" so that it does not cut
  // into the feature; a boundary running on ∂Ωf (0 allows it) puts the feature's own border onto
  // the target, and Eq. 3.1's length weight draws it there (docs/decisions.md).
  int feature_clearance = 1;
};

struct BoundaryIteration;
// Called by optimize() after each iteration's fit (k from 0), for progress in an app.
using BoundaryProgress = std::function<void(int k, const BoundaryIteration& it)>;

struct BoundaryIteration {
  double energy = 0;                // E(B_k, T_k)
  double step_energy = 0;           // E(B_k+1, T_k): the boundary step's loop under the same T (<= energy;
                                    // NaN in the last entry, where the iteration stopped)
  geometry::Similarity3 transform;  // T_k = s_k R_k (t_k: the rigid fit's translation)
  int loop_vertices = 0;            // |B_k|
  double loop_length = 0;           // Σ length(e) over B_k
  double ms = 0;                    // the fit and the boundary step
};

struct OptimalBoundaryTimings {
  double fill_ms = 0, lscm_ms = 0, cut_ms = 0;  // the optimizer's set-up
  double map_ms = 0, iterate_ms = 0;            // optimize()
};

struct OptimalBoundary {
  std::vector<int> loop;  // source vertices of the best boundary, Ωf on its left (as ∂Ω0 runs)
  double energy = 0;      // E(loop, transform)
  geometry::Similarity3 transform;
  std::vector<int> user_loop;  // ∂Ω0, the same way round
  double user_energy = 0;      // E(∂Ω0, T_0)
  std::vector<BoundaryIteration> history;
  int best_iteration = 0;  // history index of `loop`
  std::string stopped_by;  // "fixed point", "energy change" or "iteration cap"
  // Per source vertex: its image on the target (NaN for vertices off the band and for band
  // vertices mapped outside Ω1) and that image in Ω1's parameterization.
  Vertices image;
  Eigen::MatrixX2d image_uv;
  OptimalBoundaryTimings timings;
};

// The set-up (region checks, fill, both parameterizations, the cut) once; optimize() per
// placement, as an app re-runs it while the user drags the band's parameterization.
class BoundaryOptimizer {
 public:
  // Throws InvalidArgument "mesh_merge::optimal_boundary(): ..." for a face index out of range, a
  // feature face outside Ω0, an empty feature, a feature that is not connected or has more than
  // one boundary loop, a band that is not an annulus between ∂Ω0 and ∂Ωf (Ωf touching ∂Ω0
  // included), a band too narrow for a closed path options.feature_clearance edges from Ωf,
  // and an Ω1 that is not a disk.
  BoundaryOptimizer(TriMesh source, TriMesh target, BoundaryRegions regions, OptimalBoundaryOptions options = {});

  // The band's parameterization at the band's own 3D scale, turned so that the uv axes point the
  // same ways in space on both meshes, centred on Ω1's point nearest ∂Ω0's centroid: right when
  // the user placed the source roughly where it goes. Where ∂Ω0 would then leave Ω1, centred on
  // Ω1's point farthest from its border instead, and shrunk (by 0.85 at a time) until it fits.
  Placement2D suggested_placement() const;

  // The iteration of §3.4.3 from B_0 = ∂Ω0; returns the boundary of lowest energy seen. Throws
  // InvalidArgument when a vertex of ∂Ω0 maps outside Ω1 (naming it) and when every closed path
  // around Ωf crosses the outside of Ω1.
  OptimalBoundary optimize(const Placement2D& placement, const BoundaryProgress& progress = {}) const;

  // §3.4.1's merge along the boundary (the optimal one, or the user's ∂Ω0 with T_0 to compare):
  // the source cut along it (the faces it encloses with Ωf), its short boundary refined
  // (§2.5), each boundary vertex moved to its image with the deformation gradient T.linear()
  // (positions alone leave Eq. 2.8 a near-null space when the boundary is nearly planar), the
  // rest by implicit Laplacian editing (options.implicit, Eq. 2.11 by default) with Ωf moved by
  // one similarity (§3.5's shared gradient, options.hold_feature); on the target,
  // the Ω1 faces under the boundary's image in uv removed; the gap bridged and smoothed as in
  // §3.3.1 (options' smoothing, which leaves Ωf alone). Result fields as for Merger::merge() (source_map: -1 for
  // source vertices outside the boundary). Throws InvalidArgument
  // "mesh_merge::optimal_boundary(): ..." when the faces under the image are not one disk away
  // from Ω1's border.
  MergeResult merge(const OptimalBoundary& boundary, const MergeOptions& options = {},
                    bool along_user_boundary = false) const;

  // The cheapest closed path around Ωf for fixed per-vertex images and T (the boundary step;
  // +inf cost and an empty loop when none exists), oriented like ∂Ω0.
  std::vector<int> cheapest_loop(const Vertices& image, const geometry::Similarity3& T, double* cost = nullptr) const;

  const TriMesh& source() const { return source_; }
  const TriMesh& target() const { return target_; }
  const std::vector<int>& outer_loop() const { return outer_; }  // ∂Ω0, Ωf on its left
  const std::vector<int>& inner_loop() const { return inner_; }  // ∂Ωf, the same way round
  const std::vector<int>& band_faces() const { return band_faces_; }
  const std::vector<int>& feature_faces() const { return feature_faces_; }
  const std::vector<int>& target_faces() const { return target_faces_; }
  const std::vector<int>& cut() const { return cut_; }  // ∂Ω0 ... ∂Ωf, the shortest path across the band
  bool fill_is_fan() const { return fill_is_fan_; }
  // Per source vertex the normalized parameterization (NaN off the band) and per target vertex
  // Ω1's (NaN off Ω1).
  const Eigen::MatrixX2d& source_uv() const { return source_uv_; }
  const Eigen::MatrixX2d& target_uv() const { return target_uv_; }
  const OptimalBoundaryTimings& setup_timings() const { return timings_; }

 private:
  void find_loops();
  void parameterize_band(const TriMesh& band);
  void parameterize_target();
  void cut_band(const TriMesh& band, const geometry::Connectivity& conn);
  void keep_clear_of_feature(const geometry::Connectivity& band);
  std::vector<int> faces_inside(const std::vector<int>& loop) const;
  std::vector<int> faces_under(const Eigen::MatrixX2d& polygon) const;  // Ω1-local face indices
  bool hole_reaches_border(const std::vector<int>& region_faces) const;
  Eigen::Vector3d point_at(const Eigen::Vector2d& uv) const;
  Eigen::Vector2d deepest_target_point() const;
  void zip_onto_target(MergeResult& r, const Faces& part_faces, const std::vector<int>& part_loop,
                       const Eigen::MatrixX2d& loop_uv) const;

  TriMesh source_, target_;
  OptimalBoundaryOptions options_;
  std::vector<int> band_faces_, feature_faces_, target_faces_;
  std::vector<int> outer_, inner_, cut_;
  bool fill_is_fan_ = false;
  Eigen::MatrixX2d source_uv_, target_uv_;
  TriMesh cut_band_;         // the band cut open: vertex nv + k is cut_[k]'s twin
  std::vector<int> origin_;  // cut_band_ vertex -> source vertex
  std::shared_ptr<const geometry::Connectivity> cut_conn_;
  std::vector<char> too_near_;         // per source vertex: closer to Ωf than feature_clearance
  TriMesh target_region_;              // Ω1 alone, compact
  std::vector<int> target_vertex_;     // its vertices' target indices
  Eigen::MatrixX2d target_region_uv_;  // its parameterization
  OptimalBoundaryTimings timings_;
};

// Eq. 3.1 for a closed loop of source vertices: Σ ‖T.linear() e − e*‖ ‖e‖ over its edges, with e
// the edge on the source and e* between the endpoints' images (+inf where an image is NaN).
double boundary_energy(const Vertices& source, const Vertices& image, const std::vector<int>& loop,
                       const geometry::Similarity3& T);

// BoundaryOptimizer(...).optimize(placement).
OptimalBoundary optimal_boundary(const TriMesh& source, const TriMesh& target, const BoundaryRegions& regions,
                                 const Placement2D& placement, const OptimalBoundaryOptions& options = {});

}  // namespace lapis::mesh_merge
