// Deformation transfer by handle correspondence (Au et al. 2007, §6): the source's deformation
// is fitted as one translation-free 3×3 transform per isoline from all its edges (Eq. 11), and
// the target, whose handles correspond one to one (so its isoline (i, j) is the source's), is
// rebuilt from its own edges turned by those transforms (Eq. 12), one vertex held.
#pragma once

#include <memory>
#include <vector>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/handle_fields.h"

namespace lapis::mesh_deform {

struct TransferOptions {
  int isolines = 20;          // n_iso, the same on both meshes (§6: "the same number of isolines")
  HandleFieldOptions fields;  // point handles' discs, relative to each mesh's own diagonal
};

struct TransferReport {
  int handles = 0;           // H on each mesh, the fixed region included
  int unknowns = 0;          // 3 K n_iso per coordinate (Eq. 11)
  double eq11_residual = 0;  // last transfer: ‖W_e R_e − E X‖ / ‖E X‖ on the source
  double eq12_residual = 0;  // the same of Eq. 12 on the target
  std::vector<int> pinned;   // target vertices held (one per connected component)
  double setup_ms = 0;
};

// The handles are Selections as the deformers take them: the ROI's complement is the fixed
// region (handle 0), then the region handles and the point handles, each paired with the
// target's of the same index. Throws InvalidArgument "mesh_deform::DeformationTransfer: ..."
// when the counts of region or point handles differ, one mesh has a fixed region and the other
// not, or isolines < 2; and what make_layout() and harmonic_fields() throw for either mesh.
class DeformationTransfer {
 public:
  DeformationTransfer(const TriMesh& source, const Selection& source_handles, const TriMesh& target,
                      const Selection& target_handles, TransferOptions options = {});
  ~DeformationTransfer();

  // The target deformed like `source_deformed` (#V_source by 3) deforms the source. With at
  // least three handles the source's transforms are first carried into the target's frame
  // (the similarity of the handles' centroids); the held vertex moves with handle 0's centroid.
  // Throws InvalidArgument for a wrong row count or a non-finite position.
  Vertices transfer(const Vertices& source_deformed);

  const TransferReport& report() const { return report_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  TransferReport report_;
};

}  // namespace lapis::mesh_deform
