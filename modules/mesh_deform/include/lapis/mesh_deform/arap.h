// As-rigid-as-possible surface modeling (Sorkine & Alexa 2007): alternate per-vertex rotation
// fits (local step, parallel) and a global Poisson solve with the cotangent Laplacian
// factorized once. The method every peer library ships, and the local step Zhao et al. use.
#pragma once

#include <memory>

#include "lapis/mesh_deform/cold_start.h"
#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform {

struct ArapOptions {
  int max_iterations = 10;  // per deform(); Sorkine & Alexa report 2–3 suffice while dragging
  // Stop early once the energy's relative decrease falls below this; 0: always run
  // max_iterations (benchmarks, reproducible results).
  double tolerance = 0.0;
  // Start from the rotations of the previous frame's result (interactive drag, Sorkine &
  // Alexa §4) rather than from cold_start's.
  bool warm_start = true;
  ColdStart cold_start = ColdStart::HandleRotations;
};

struct ArapReport {
  int iterations = 0;          // in the last deform()
  double energy = 0;           // Σ_i Σ_j w_ij ‖ẽ_ij − R_i e_ij‖² of the result, R_i its best rotations
  int rotation_fallbacks = 0;  // rotation fits that needed the SVD fallback (last frame)
  double setup_ms = 0;
  double frame_ms = 0;
  double rotations_ms = 0;  // local steps of the last frame (with right-hand sides)
  double solves_ms = 0;     // global steps of the last frame
  double ms_per_iteration() const { return iterations ? frame_ms / iterations : 0; }
};

class ArapDeformer final : public Deformer {
 public:
  explicit ArapDeformer(TriMesh mesh, ArapOptions options = {});
  ~ArapDeformer() override;
  void set_options(const ArapOptions& options);  // does not invalidate the factorization
  const ArapOptions& options() const { return options_; }
  const ArapReport& report() const { return report_; }
  // Forgets the previous frame (the next deform() starts from the rest mesh).
  void reset_warm_start();
  std::string name() const override { return "arap"; }

 protected:
  void setup(const Layout& layout) override;
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  struct Impl;
  ArapOptions options_;
  ArapReport report_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lapis::mesh_deform
