// Deformation for an interactive session: keeps one deformer set up across frames and
// re-runs the setup only when the method settings or the selection change (thesis §2.5:
// precompute once per ROI/handle set, back-substitute per frame), records every frame it
// solved since that setup (so a CLI run of the same frames reproduces the result: the
// implicit method's rotation unwrapping and ARAP's warm start depend on them), computes the
// per-vertex distortion the app colours the surface with, and keeps the salient method's
// feature detection across setups. Not thread-safe: one caller
// (the app's worker thread) at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lapis/mesh_deform/isolines.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/mesh_deform/vertex_distortion.h"

namespace lapis::mesh_deform {

inline constexpr int kIsolinePreviewStride = 8;

struct LiveRequest {
  MethodSettings settings;
  Selection selection;
  std::uint64_t selection_revision = 0;  // the caller bumps it when the selection changes
  HandleTransforms transforms;
  // While dragging: the implicit method's first system only (§2.5); the isolines method's
  // iteration with every kIsolinePreviewStride-th free vertex reconstructed (§5: a subset is shown).
  bool preview = false;
  std::optional<DistortionField> field;  // per-vertex distortion to compute, if any
  // Salient method: features given by the user (painted), combined with the detected ones by
  // settings.salient.user_features; the caller bumps features_revision when they change.
  std::vector<Feature> features;
  std::uint64_t features_revision = 0;
};

struct LiveFrame {
  Vertices positions;          // #V by 3
  Eigen::VectorXd distortion;  // #V, empty when no field was requested
  bool did_setup = false;      // this frame ran the setup
  bool preview = false;        // this frame was a preview (first system only, or a subset reconstructed)
  double setup_ms = 0;         // of the current setup (whenever it ran)
  double solve_ms = 0;         // this frame's deform() call
  double distortion_ms = 0;
  std::string method;                     // deformer name
  std::string timing;                     // the method's own breakdown of the frame ("Eq. 2.8 12 ms, ...")
  double energy = -1;                     // ARAP: the result's energy (ArapReport::energy); -1 for the others
  std::vector<int> degenerate_vertices;   // implicit: found by the current setup
  std::vector<HandleTransforms> history;  // every frame solved since the setup, this one last
  // Salient method: the saliency (empty without detection) and the features in use.
  Eigen::VectorXd saliency;
  std::vector<Feature> features;
  // Isolines method, on a setup frame: the harmonic field of the first isoline set (§4.1), the
  // rigidity ψ (#V each) and that set's isolines on the rest mesh. Empty otherwise.
  Eigen::VectorXd isoline_field, rigidity;
  std::vector<IsolineSegment> isolines;
};

class LiveDeformer {
 public:
  // rest  #V by 3 / #F by 3; copied once.
  explicit LiveDeformer(TriMesh rest);
  ~LiveDeformer();

  // Sets up when the settings or the selection revision differ from the last call, then
  // solves this frame. Throws what the deformer throws (InvalidArgument for a bad selection:
  // the next call sets up again).
  LiveFrame update(const LiveRequest& request);

  const TriMesh& rest() const { return rest_; }

 private:
  void prepare_salient(SalientDeformer& d, const LiveRequest& r);

  TriMesh rest_;
  std::unique_ptr<Deformer> deformer_;
  MethodSettings settings_;
  std::uint64_t selection_revision_ = 0, features_revision_ = 0;
  // The salient method's detection, run once per mesh and detection options, not once per
  // selection (it costs seconds where a setup costs milliseconds).
  std::optional<SalientFeatures> detection_;
  FeatureOptions detection_options_;  // what detection_ was run with
  double setup_ms_ = 0;
  std::vector<HandleTransforms> history_;
};

}  // namespace lapis::mesh_deform
