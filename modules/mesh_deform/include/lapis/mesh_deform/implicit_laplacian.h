// Implicit Laplacian mesh editing (thesis ch. 2, §2.4–2.5): per-vertex deformation gradients
// M_i implicitly defined by the vertex and its 1-ring (Eq. 2.3–2.5), kept coherent over 2-ring
// pairs (Eq. 2.7) and solved together with the positions (Eq. 2.8); degenerate vertices
// displaced and pulled back (§2.4.3); shearing removed by polar decomposition and a second
// Laplacian solve (§2.4.4, Eq. 2.10/2.11). Both systems are prefactorized (§2.5).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/laplacian_weights.h"

namespace lapis::mesh_deform {

enum class ShearingRemoval {
  None,            // first system only (+ degenerate pull-back): §2.5's preview while dragging
  RetainFeatures,  // D(ṽ_i) = R_i δ_i        (Eq. 2.10), for rigid handle transforms
  ScaleFeatures,   // D(ṽ_i) = R_i S_i δ_i    (Eq. 2.11), for handles that scale
};

struct ImplicitOptions {
  LaplacianWeights weights = LaplacianWeights::Cotangent;      // §2.4.3: uniform weights drift tangentially
  ShearingRemoval shearing = ShearingRemoval::RetainFeatures;  // §2.4.4, Eq. 2.10
  double degenerate_condition = 2.0e5;  // §2.4.3: cond(V_i V_iᵀ) above this marks a degenerate vertex
  double s_disp = 0.2;                  // §2.4.3, Eq. 2.9: displacement scale of degenerate vertices
  // Eq. 2.8 adds E_L and E_R unweighted. E_L is in squared lengths and E_R dimensionless, so
  // both soft weights below are multiplied by the squared mean edge length: the result is then
  // independent of the mesh's scale, and equal to Eq. 2.8 on a unit-edge mesh.
  double coherence_weight = 1.0;  // Eq. 2.7 term
  double transform_weight = 1.0;  // Eq. 2.8 transformation constraints M_c = W_c at handles and at the fixed border
  // Handle rotations accumulated over a drag (each deform() call continues the previous
  // frame's angle) beyond guide_angle switch to a system with guide transformation
  // constraints on bands between the fixed region and the handle, each turned by its share of
  // the angle: the "more handles" remedy of §2.5, automated, so a handle turned past π is
  // honoured. The guide system is factorized on the first frame that needs it. Off: the
  // thesis' plain method (which takes the smaller angle).
  bool large_rotations = true;
  double guide_angle = 0.5 * 3.141592653589793;  // below it both systems agree closely
  // Weight of the guide bands' transformation rows, relative to transform_weight. As weak as
  // the handles' rows, E_L and E_R outweigh them on real meshes and the turn takes the short
  // way (a 270° twist left the camel's mid-body at 24° instead of 135°); 100 holds it (124°),
  // and more changes nothing.
  double guide_weight = 100;
  // Eq. 2.8's solution is affine in the handle transforms (its right-hand side and fixed
  // values are linear in them). With at most this many handle parameters (4 per region
  // handle: the columns of its 3×4 transform act alike on x, y and z; 1 per point handle),
  // setup solves once for one column per parameter and each frame combines them: a
  // #V × parameters product instead of the first back-substitution, equal to it up to
  // rounding. 0: back-substitute every frame.
  int max_basis_columns = 64;
  // Corrections of each back-substitution from the blocks' own residuals
  // (solver::LeastSquares::solve with refinement steps). Eq. 2.8's normal matrix squares the
  // conditioning of its rows: on a 13K-vertex head held only at its neck it is ~1e11, and a
  // solve carries ~1e-5 of the diagonal of rounding, which a similarity of the input reshuffles.
  // One step takes that to ~1e-11 for one more back-substitution and product per system.
  // 0 for interactive editing, where a frame's rounding is far below what the eye sees.
  int refinement_steps = 0;
  // Weight of a shared-gradient group's edge rows (set_shared_gradients, thesis §3.5) in Eq.
  // 2.10/2.11, against the Laplacian rows' 1: how firmly the group keeps its shape. 100 let a
  // feature one ring from a merging boundary bend by 1.6–3.5% of its size; 1000 holds it to
  // 0.04–0.2% (docs/decisions.md).
  double group_weight = 1000;
};

// One extra least-squares row of the first system: vertex's transformed Laplacian coordinate
// M_i δ_i minus a barycentric blend Σ_j b_j M_j δ_j of three others (thesis §3.3.3, the
// transition term E_T of Poisson merging, which couples the ROIs of two meshes held in one).
struct LaplacianBlend {
  int vertex = -1;
  std::array<int, 3> others{-1, -1, -1};
  std::array<double, 3> weights{0, 0, 0};
};

// What the last deform() did and cost.
struct ImplicitReport {
  int free_vertices = 0;
  int degenerate_vertices = 0;      // displaced by Eq. 2.9 (incl. boundary variants)
  int inserted_vertices = 0;        // midpoints inserted for boundary vertices of valence < 3
  int polar_fallbacks = 0;          // rotation fits that needed the SVD fallback (last frame)
  bool guided = false;              // last frame used the large-rotation guide system
  long long first_factor_nnz = 0;   // non-zeros of the Cholesky factors of Eq. 2.8's and
  long long second_factor_nnz = 0;  // Eq. 2.10's normal matrices
  double setup_ms = 0;              // assembly + both factorizations
  int basis_columns = 0;            // > 0: Eq. 2.8 combined from that many precomputed solutions
  double first_solve_ms = 0;        // Eq. 2.8 back-substitution (x, y, z together) or combination
  double polar_ms = 0;              // all gradients M_i and their polar decompositions
  double second_solve_ms = 0;       // Eq. 2.10/2.11 back-substitution
  double frame_ms = 0;              // the whole deform() call
};

class ImplicitLaplacianDeformer final : public Deformer {
 public:
  explicit ImplicitLaplacianDeformer(TriMesh mesh, ImplicitOptions options = {});
  ~ImplicitLaplacianDeformer() override;

  // Changing options re-runs setup on the next deform(), which also restarts the drag (the
  // accumulated handle rotations).
  void set_options(const ImplicitOptions& options);
  const ImplicitOptions& options() const { return options_; }
  const ImplicitReport& report() const { return report_; }
  std::string name() const override { return "implicit"; }

  // §2.5's preview while dragging: with preview on, deform() stops after the first system (as
  // ShearingRemoval::None does) but keeps the second system's factorization, so turning it
  // off again (on release) gives the full pipeline without a new setup. The accumulated
  // handle rotations carry on either way.
  void set_preview(bool on) { preview_ = on; }
  bool preview() const { return preview_; }

  // Adds w Σ ‖M_i δ_i − Σ_j b_j M_j δ_j‖² to Eq. 2.8 (thesis §3.3.3; w = 0.1 there). E_T is in
  // the units of E_L, so w is not scaled by the edge length. Terms at vertices whose M_i is
  // not used (no free vertex within 2 rings) are constants and left out. Marks the deformer
  // dirty. Throws InvalidArgument "mesh_deform::ImplicitLaplacianDeformer::set_laplacian_blends(): ..."
  // for w <= 0 or NaN, a vertex out of range, or a weight that is not finite.
  void set_laplacian_blends(std::vector<LaplacianBlend> blends, double weight);

  // Thesis §3.5: each group of vertices (a feature) shares one deformation gradient, implicitly
  // defined over the group as a 1-ring's is over the 1-ring (the least-squares linear map of the
  // rest group onto the deformed one, fitted on at most 32 of its vertices spread over it), so
  // every Laplacian coordinate of the feature is transformed alike and the feature moves by one
  // transformation (after §2.4.4's shear removal, a similarity) instead of bending with its
  // surroundings: Eq. 2.10/2.11 also holds the group's edges to that transformation (weight
  // options.group_weight), without which the group would still bend with its surroundings
  // through its border. Marks the deformer dirty. Throws InvalidArgument
  // "mesh_deform::ImplicitLaplacianDeformer::set_shared_gradients(): ..." for a group of fewer
  // than 4 vertices, a vertex out of range or in two groups.
  void set_shared_gradients(std::vector<std::vector<int>> groups);

  // Original vertices the last setup found degenerate or displaced (§2.4.3), ascending.
  std::vector<int> degenerate_vertices() const;

 protected:
  void setup(const Layout& layout) override;
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  void build_guide(const std::vector<int>& handles);
  struct Impl;
  ImplicitOptions options_;
  ImplicitReport report_;
  bool preview_ = false;
  std::vector<LaplacianBlend> blends_;
  double blend_weight_ = 0;
  std::vector<std::vector<int>> shared_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lapis::mesh_deform
