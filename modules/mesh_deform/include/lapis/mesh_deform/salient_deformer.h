// Salient-feature-preserving deformation in a solid subspace (Zhao et al. 2016): salient
// features (§3.1) stay rigid by shape matching (Eq. 1–2), the rest keeps its cotangent
// Laplacian detail (Eq. 3), handles are soft (Eq. 4), and everything is solved for the
// positions and linear maps of a coarse enclosing tetrahedral mesh (Eq. 7–11), so each
// iteration costs a back-substitution of a few hundred unknowns plus O(#V) local fits.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lapis/geometry/tet_mesh.h"
#include "lapis/mesh_deform/cold_start.h"
#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/salient_features.h"

namespace lapis::mesh_deform {

// w_i of Eq. 2, which "simply take[s] its size into account" (§3.2).
enum class FeatureWeight {
  Size,     // w_i = |F_i| / mean |F| (spec §5.3; Eq. 1 already sums over the vertices)
  Uniform,  // w_i = 1
};

struct SalientOptions {
  double alpha = 1.0;   // Eq. 10: weight of E_ldp (the paper's default)
  double beta = 2.0;    // Eq. 10: weight of E_p, the soft handles
  double gamma = 1.0;   // Eq. 10: weight of E_disc
  double lambda = 1.0;  // Eq. 10: weight of E_vibr
  int iterations = 5;   // per deform(); §5: "three to five iterations"
  FeatureWeight feature_weight = FeatureWeight::Size;
  double feature_weight_scale = 1.0;  // multiplies every w_i (rigidity against the rest)
  // Vertices of the enclosing lattice when no subspace is given (Table 1: 51–227).
  int subspace_vertices = 100;
  bool detect_features = true;  // §3.1; off: only the features given by set_features()
  FeatureOptions detection;
  FeatureMerge user_features = FeatureMerge::Union;  // how set_features() combines with detection
  // Start a frame from the rotations the previous one ended with (an interactive drag);
  // otherwise from cold_start's. HandleRotations blends the handles' rotations over a field
  // solved in the subspace, nearly constant on each feature (which takes its mean); Identity is
  // the spec's R = I (§1.4).
  bool warm_start = true;
  ColdStart cold_start = ColdStart::HandleRotations;

  bool operator==(const SalientOptions&) const = default;
};

struct SalientReport {
  int features = 0, feature_vertices = 0;
  int subspace_vertices = 0, tets = 0, unknowns = 0;  // unknowns per coordinate: 4 · subspace_vertices
  int strays = 0;                                     // surface vertices outside every tet
  FeatureReport detection;
  double detection_ms = 0;   // HKS, clustering, aggregation (once per mesh)
  double subspace_ms = 0;    // building the tetrahedra (once per mesh)
  double embedding_ms = 0;   // location and C (once per mesh)
  double system_ms = 0;      // system (11) without the handle rows (once per mesh)
  double precompute_ms = 0;  // Table 1's precomputation: system_ms, the handle rows, the Cholesky, the start's fields
  double factorize_ms = 0;   // of which the factorization
  int iterations = 0;        // in the last deform()
  double frame_ms = 0, rotations_ms = 0, solves_ms = 0, interpolation_ms = 0;
  double last_change = 0;       // max vertex move of the last iteration / bounding box diagonal
  double handle_residual = 0;   // max ‖p′_h − p̄_h‖ over constrained vertices, before they are placed
  double feature_residual = 0;  // max feature_rigidity_residual() over the features
  double ms_per_iteration() const { return iterations ? frame_ms / iterations : 0; }
};

class SalientDeformer final : public Deformer {
 public:
  explicit SalientDeformer(TriMesh mesh, SalientOptions options = {});
  ~SalientDeformer() override;

  // Throws InvalidArgument for weights that are negative or not finite, alpha, beta or gamma +
  // lambda not positive, iterations < 1 or subspace_vertices < 8. Invalidates the precompute.
  void set_options(const SalientOptions& options);
  const SalientOptions& options() const { return options_; }
  // User features (§3.1), combined with the detected ones by options().user_features.
  // Indices are checked by the next precompute() (combine_features()).
  void set_features(std::vector<Feature> features);
  // A given solid subspace (e.g. from a tetrahedral mesher) instead of the lattice. Checked by
  // the next precompute(): geometry::require_valid_tets().
  void set_subspace(geometry::TetMesh tets);
  // A detection already run on this mesh (e.g. cached by an interactive session across
  // selections), used instead of running options().detection again. Throws InvalidArgument
  // when its saliency has not one value per vertex.
  void set_detection(SalientFeatures detection);

  // After precompute(): the features in use, the saliency (empty without detection) and the
  // subspace with its coordinates.
  const std::vector<Feature>& features() const;
  const Eigen::VectorXd& saliency() const;
  const geometry::TetMesh& subspace() const;
  const SalientReport& report() const { return report_; }
  void reset_warm_start();
  std::string name() const override { return "salient"; }

 protected:
  void setup(const Layout& layout) override;
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  struct Model;  // per mesh, features and subspace: detection, C, the selection-free system
  struct Frame;  // per selection: the factor, rotations, the last iterate
  void build_model();
  void build_handle_fields(Frame& frame, const Layout& layout) const;
  void start_cold(Frame& frame, const HandleTransforms& transforms) const;
  SalientOptions options_;
  SalientReport report_;
  std::vector<Feature> user_features_;
  std::optional<geometry::TetMesh> given_subspace_;
  std::optional<SalientFeatures> detection_;  // kept across set_features() and selections
  std::unique_ptr<Model> model_;
  std::unique_ptr<Frame> frame_;
};

}  // namespace lapis::mesh_deform
