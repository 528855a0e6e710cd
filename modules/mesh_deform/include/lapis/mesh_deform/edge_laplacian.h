// Edge-based Laplacian mesh deformation (Wang, Zheng & Seah): the Laplacian lives on the
// mesh's edges (§3.3: each edge midpoint against the midpoints of the edges sharing an
// endpoint), each node's Laplacian vector is turned and stretched by T = S R1 fitted to its
// cell (§3.4, Eq. 7–8), and Eq. 6 is re-solved a few times with one factorization.
// The vertex-based variant with the same transform estimation (§4's comparison) is an option.
#pragma once

#include <memory>
#include <string>

#include "lapis/mesh_deform/cold_start.h"
#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/laplacian_weights.h"

namespace lapis::mesh_deform {

// Where the Laplacian vectors live.
enum class LaplacianDomain {
  Edges,     // §3.3: one node per edge, ~3 #V rows
  Vertices,  // §3.1 Eq. 1: one node per vertex, the paper's §4 baseline
};

// What T_i may do to its cell (Eq. 7–8).
enum class CellTransform {
  Rotation,          // T = R1 (Sorkine & Alexa's fit only)
  IsotropicScale,    // T = s R1
  AnisotropicScale,  // T = S R1, the paper's choice (§3.4: R2 "has little effect")
  Full,              // T = R2 S R1 with R2 fitted after S (§3.4), for experiments
};

// The axes of the anisotropic scale S.
enum class ScaleFrame {
  // §3.4: "the x, y and z of Cartesian coordinates". Not rotation-equivariant: a limb that is
  // not along a world axis gets no anisotropy.
  World,
  // The principal axes U of the node's rest cell, T = R1 U S Uᵀ; equal eigenvalues share one
  // scale, so the result does not depend on the frame the mesh is given in.
  RestPrincipal,
};

struct EdgeLaplacianOptions {
  LaplacianDomain domain = LaplacianDomain::Edges;  // §3.3
  // Vertex domain: Eq. 1 uniform 1/|N(i)| or Eq. 2 cotangent (without Ω_i). Edge domain
  // (the paper gives no weights there): uniform 1/|N(e)|, or each neighbouring edge weighted
  // by its own cotangent weight. Negative cotangents are kept in D and clamped to 0 in the fits.
  LaplacianWeights weights = LaplacianWeights::Uniform;       // §3.1: "a simple scheme"
  CellTransform transform = CellTransform::AnisotropicScale;  // §3.4: T ≈ S R1
  ScaleFrame frame = ScaleFrame::World;                       // §3.4, literal
  int iterations = 4;  // T-updates per deform() after the first solve; §4: "three to four"
  // Stop early once an iteration moves no vertex by more than tolerance × bbox diagonal; 0:
  // always run `iterations` (with scale the iteration drifts instead of converging).
  double tolerance = 0.0;
  // Start a frame from the previous frame's transforms instead of cold_start's.
  bool warm_start = false;
  // The paper leaves the start open. HandleRotations: each node's T starts as the blend of the
  // region handles' rotations and log-scales by their harmonic fields (Dᵀ D φ = 0, 1 on the
  // handle), so a similarity shared by every handle is the first solve; Identity: T = I, a
  // naive edge-Laplacian solve first.
  ColdStart cold_start = ColdStart::HandleRotations;
  // §3.2: Eq. 6 penalizes handles with weight 1 ("behaves better"); default hard, the
  // Deformer contract (handles land exactly).
  bool soft_handles = false;
  double handle_weight = 1.0;  // Eq. 6

  bool operator==(const EdgeLaplacianOptions&) const = default;
};

struct EdgeLaplacianReport {
  int nodes = 0;         // Laplacian nodes whose row enters the system
  int rows = 0;          // rows of D (= nodes)
  int unknowns = 0;      // solved vertices
  long factor_nnz = 0;   // non-zeros of the Cholesky factor of DᵀD
  int iterations = 0;    // T-updates in the last deform()
  double last_move = 0;  // largest vertex move of the last iteration, mesh units
  int rotation_fallbacks = 0;
  double setup_ms = 0;
  double frame_ms = 0;
  double fit_ms = 0;    // transform fits of the last frame (with right-hand sides)
  double solve_ms = 0;  // back-substitutions of the last frame
};

// precompute() throws as Deformer's does, and NotPositiveDefinite
// "mesh_deform::EdgeLaplacianDeformer::precompute(): ..." naming a vertex (column()) of a part of
// the free vertices that no handle or fixed vertex holds.
class EdgeLaplacianDeformer final : public Deformer {
 public:
  // Throws InvalidArgument like set_options().
  explicit EdgeLaplacianDeformer(TriMesh mesh, EdgeLaplacianOptions options = {});
  ~EdgeLaplacianDeformer() override;
  // Throws InvalidArgument "mesh_deform::EdgeLaplacianDeformer::set_options(): ..." for
  // iterations < 1, a negative or non-finite tolerance or a handle weight not finite and > 0.
  // Marks the deformer dirty when the domain, weights, scale frame or handle mode change.
  void set_options(const EdgeLaplacianOptions& options);
  const EdgeLaplacianOptions& options() const { return options_; }
  const EdgeLaplacianReport& report() const { return report_; }
  // Forgets the previous frame's transforms.
  void reset_warm_start();
  std::string name() const override { return "edge"; }

 protected:
  void setup(const Layout& layout) override;
  bool needs_face_shapes() const override { return options_.weights == LaplacianWeights::Cotangent; }
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  struct Impl;
  EdgeLaplacianOptions options_;
  EdgeLaplacianReport report_;
  std::unique_ptr<Impl> impl_;
};

// Names for command lines and reports: edges, vertices; rotation, isotropic, anisotropic,
// full; world, principal. The *_from_name functions throw InvalidArgument naming the known ones.
const char* to_string(LaplacianDomain d);
const char* to_string(CellTransform t);
const char* to_string(ScaleFrame f);
LaplacianDomain laplacian_domain_from_name(const std::string& name);
CellTransform cell_transform_from_name(const std::string& name);
ScaleFrame scale_frame_from_name(const std::string& name);

}  // namespace lapis::mesh_deform
