// CGAL's Surface_mesh_deformation with ORIGINAL_ARAP (Eigen SparseLU inside) behind a plain
// interface, so CGAL stays in one translation unit: the independent reference the mesh_deform
// tests check ArapDeformer against, and the peer its benchmark times.
#pragma once

#include <memory>
#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::peers {

class CgalArap {
 public:
  // Vertices outside roi stay fixed; control vertices (inside roi) are moved by set_targets.
  // The constructor inserts the ROI and control vertices and factorizes (CGAL's preprocess).
  CgalArap(const geometry::TriMesh& mesh, const std::vector<int>& roi, const std::vector<int>& control);
  ~CgalArap();
  CgalArap(const CgalArap&) = delete;
  CgalArap& operator=(const CgalArap&) = delete;

  // targets  #V by 3: the rows of the control vertices are read.
  void set_targets(const geometry::Vertices& targets);
  // CGAL's deform(iterations, tolerance): stops early once the energy's relative change is
  // below tolerance (0: always `iterations`). Continues from the current positions.
  void deform(unsigned iterations, double tolerance);
  geometry::Vertices positions() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> control_;
};

}  // namespace lapis::peers
