// Handle-aware isolines (Au, Fu, Tai & Cohen-Or 2007): a reduced model of iterative Laplacian
// editing (§3, Eq. 1–3) whose unknowns are one 3×4 transformation per isoline of per-handle
// harmonic fields (§4.1, Eq. 4–5), interpolated to the vertices by the fields (§4.2, X = W_x R_x)
// and, for the Laplacian coordinates, to sampled isoline triangles (§4.3, δ = W_δ R_δ), so that
// an iteration of Eq. 10 costs the same at 20K and at 2M vertices. Eq. 6 (positions reduced,
// Laplacian coordinates from the whole mesh each iteration) is the other mode.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/handle_fields.h"
#include "lapis/mesh_deform/isolines.h"

namespace lapis::mesh_deform {

// Which of the paper's reduced updates runs.
enum class IsolineSolve {
  Reduced,  // Eq. 10: per-isoline fits on sampled triangles; an iteration is independent of #V (t₂)
  Full,     // Eq. 6: δ(W_x R_x) over the whole mesh each iteration; O(#V) per iteration (t₁)
};

// How an isoline's transformation r̂ of its Laplacian coordinates is fitted (Eq. 8).
enum class IsolineFit {
  Rotation,    // the nearest rotation to Σ l_k² n_k n̄_kᵀ; defined on coplanar normals (a bar's rings)
  Similarity,  // that rotation times the isoline's length ratio: models handle scaling
  Paper,       // Eq. 9 as printed (pseudo-inverse of the rank-2 matrix of coplanar normals); can shear
};

struct IsolinesOptions {
  int isolines = 20;                           // n_iso per handle (§4.1, §5: "20 usually sufficient")
  IsolineSolve solve = IsolineSolve::Reduced;  // Eq. 10 (§4.3)
  IsolineFit fit = IsolineFit::Rotation;       // Eq. 8; Eq. 9 is singular on coplanar normals
  double omega = 1000;  // §3, Eq. 2: soft handle weight, relative to a mean Laplacian row (see docs)
  // §4.2: isoline smoothness (Eq. 5), β² relative to ‖L W_x‖²_F / ‖M‖²_F. The paper's 0.01 is
  // in its own units; relative to the Laplacian part it lets a free part swing on the armadillo
  // (an arm 0.33 of the diagonal away for a 0.017 handle move), 0.1 holds it (see decisions).
  double beta = 0.1;
  // n_tri bound of §4.3 (value not given): 0 means 30 per isoline, Table 1's 24–32.
  int triangle_budget = 0;
  int min_triangles_per_isoline = 8;  // so that a sparse isoline still has ≥ 3 non-coplanar normals
  int max_iterations = 50;            // per deform() (§5: "average n_iter is less than 20")
  double tolerance = 1e-4;  // stop when ‖R^{t+1} − R^t‖ / ‖R^t‖ falls below it (Fig. 11's step size)
  // Anderson acceleration of the iteration over this many past iterates (0: the paper's plain
  // inexact Gauss–Newton). Same fixed point; on the armadillo 3–5 times fewer iterations.
  int anderson_depth = 3;
  // A region handle turned (over the drag, unwrapped frame to frame) past guide_angle pulls the
  // linear parts of its isolines toward their share s_j of its rotation: the "extra in-between
  // handles" of §5's limitation, placed automatically, so a turn past π is kept. Off: the
  // paper's model, which unwinds past π.
  bool large_rotations = true;
  double guide_angle = 0.5 * 3.141592653589793;
  double guide_weight = 1;    // relative to the mean diagonal of the Laplacian part of UᵀU
  HandleFieldOptions fields;  // point handles' disc (§4.1 needs a field per handle)

  bool operator==(const IsolinesOptions&) const = default;
};

struct IsolinesReport {
  int handles = 0;             // H, the fixed region included
  int sets = 0;                // K: H, or 1 when H = 2 (§4.1)
  int unknowns = 0;            // 4 K n_iso per coordinate (Eq. 4)
  int crossed_triangles = 0;   // crossed by all isolines
  int sampled_triangles = 0;   // n_tri (§4.3)
  int iteration_vertices = 0;  // vertices an Eq. 10 iteration evaluates (≤ 3 n_tri)
  int iteration_rows = 0;      // vertices an iteration touches: iteration_vertices, or #V in Eq. 6 mode
  double field_overshoot = 0;  // clamped out of [0, 1] (§5)
  double field_residual = 0;
  long long field_factor_nnz = 0;
  double fields_factorize_ms = 0, fields_solve_ms = 0, extraction_ms = 0, assembly_ms = 0, setup_ms = 0;
  int iterations = 0;         // of the last deform()
  std::vector<double> steps;  // ‖ΔR‖/‖R‖ per iteration of the last deform()
  // Per iteration of the last deform(). The first one of a frame finds the reduced system out of
  // cache (the last reconstruction streamed #V × 3 positions through it).
  std::vector<double> iteration_ms;
  double iterate_ms = 0;      // all iterations of the last deform()
  double reconstruct_ms = 0;  // X = W_x R_x over the free vertices
  double frame_ms = 0;
};

class IsolinesDeformer final : public Deformer {
 public:
  // Throws InvalidArgument like set_options().
  explicit IsolinesDeformer(TriMesh mesh, IsolinesOptions options = {});
  ~IsolinesDeformer() override;
  // Throws InvalidArgument "mesh_deform::IsolinesDeformer::set_options(): ..." for isolines < 2,
  // a weight not finite and > 0 (β may be 0), max_iterations < 1, a negative tolerance, budget or
  // anderson_depth,
  // or a point-handle radius not finite and ≥ 0. Marks the deformer dirty when the model changes.
  void set_options(const IsolinesOptions& options);
  const IsolinesOptions& options() const { return options_; }
  const IsolinesReport& report() const { return report_; }
  std::string name() const override { return "isolines"; }

  // The next deform() starts from the identity transforms instead of the last frame's.
  void reset_warm_start();
  // Preview while dragging: deform() iterates as usual but reconstructs only every
  // `stride`-th free vertex (the others keep the last frame's positions); 0 turns it off. The
  // first frame after one without preview is whole: only previews keep a copy of their result.
  void set_preview_stride(int stride) { preview_stride_ = stride < 0 ? 0 : stride; }

  // After setup: the fields (#V by H, column order of HandleSets), the rigidity ψ, and the
  // rest-mesh isolines of set i (segments with level = isoline index).
  const Eigen::MatrixXd& fields() const;
  Eigen::VectorXd rigidity() const;
  int isoline_sets() const;
  std::vector<IsolineSegment> isolines_of_set(int set) const;
  // The transforms of the last frame, 4m by 3 in normalized coordinates (block ℓ = r_ℓᵀ).
  const Eigen::MatrixXd& isoline_transforms() const;
  // Positions of `vertices` from the last frame's transforms (mesh units), |vertices| by 3.
  Vertices reconstruct(const std::vector<int>& vertices) const;

 protected:
  void setup(const Layout& layout) override;
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  struct Impl;
  IsolinesOptions options_;
  IsolinesReport report_;
  int preview_stride_ = 0;
  std::unique_ptr<Impl> impl_;
};

const char* to_string(IsolineSolve s);
const char* to_string(IsolineFit f);
// reduced, full; rotation, similarity, paper. Throw InvalidArgument naming the known ones.
IsolineSolve isoline_solve_from_name(const std::string& name);
IsolineFit isoline_fit_from_name(const std::string& name);

}  // namespace lapis::mesh_deform
