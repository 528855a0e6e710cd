// Naive Laplacian editing (thesis §2.3, Eq. 2.1): keep every Laplacian coordinate δ_i as it
// is, in the global frame. The baseline that shows why Laplacian coordinates must be
// transformed: rotating a handle shears the details instead of turning them.
#pragma once

#include <memory>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/laplacian_weights.h"

namespace lapis::mesh_deform {

struct NaiveOptions {
  LaplacianWeights weights = LaplacianWeights::Cotangent;  // §2.3
  // Hard handles are eliminated unknowns; soft handles add ‖ṽ_c − u_c‖² rows (Lipman et al.
  // 2004 use unit weights), so they only approximately reach their targets.
  bool soft_handles = false;
  double handle_weight = 1.0;
};

class NaiveLaplacianDeformer final : public Deformer {
 public:
  explicit NaiveLaplacianDeformer(TriMesh mesh, NaiveOptions options = {});
  ~NaiveLaplacianDeformer() override;
  void set_options(const NaiveOptions& options);
  const NaiveOptions& options() const { return options_; }
  std::string name() const override { return "naive"; }

 protected:
  void setup(const Layout& layout) override;
  bool needs_face_shapes() const override { return options_.weights == LaplacianWeights::Cotangent; }
  void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) override;

 private:
  struct Impl;
  NaiveOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace lapis::mesh_deform
