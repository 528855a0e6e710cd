// The interface every Lapis deformer implements: a mesh, a region of interest (ROI) and
// handles are set up once (precompute: assembly + factorization); each frame deform() maps
// handle transforms to vertex positions with back-substitutions and per-vertex local work.
// Modeled on CGAL's Surface_mesh_deformation (ROI/control sets, dirty flag, deform()).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform {

using geometry::TriMesh;
using geometry::Vertices;

// Which vertices move and how they are grabbed. Vertices outside the ROI keep their rest
// positions (the fixed region); handle vertices must lie inside the ROI.
struct Selection {
  std::vector<int> roi;                          // vertex indices, any order, no duplicates
  std::vector<std::vector<int>> region_handles;  // each moved by a rigid/similarity 4x4 transform
  std::vector<int> point_handles;                // each one vertex, translation only
};

// One frame's handle placement, parallel to Selection's handle lists.
struct HandleTransforms {
  std::vector<Eigen::Matrix4d> regions;  // applied to rest positions; bottom row (0 0 0 1)
  std::vector<Eigen::Vector3d> points;   // translation of the point handle's rest position

  // Identity transforms / zero translations for every handle of `s`.
  static HandleTransforms identity(const Selection& s);
};

// What each vertex is for the solvers (after validation).
enum class VertexRole : unsigned char { Fixed, Free, RegionHandle, PointHandle };

// The validated selection, with per-vertex roles and handle membership.
struct Layout {
  std::vector<VertexRole> role;  // #V
  std::vector<int> handle_of;    // #V: region or point handle index, -1 for Fixed/Free
  std::vector<int> free;         // ascending
  std::vector<int> constrained;  // ascending: every non-free vertex (fixed and handles)
  int num_region_handles = 0;
  int num_point_handles = 0;
};

// Base class: owns the rest mesh and the selection, validates them, keeps the dirty flag,
// and turns handle transforms into target positions. Subclasses implement the algorithm.
class Deformer {
 public:
  // mesh  #V by 3 / #F by 3; face indices must be in range and positions finite.
  explicit Deformer(TriMesh mesh);
  virtual ~Deformer();
  Deformer(const Deformer&) = delete;
  Deformer& operator=(const Deformer&) = delete;

  // Changing the selection marks the deformer dirty; the next deform() re-runs precompute().
  void set_selection(Selection selection);
  const Selection& selection() const { return selection_; }
  bool dirty() const { return dirty_; }

  // Validates the selection and runs the method's setup (assembly, factorization). Throws
  // InvalidArgument "mesh_deform::Deformer::precompute(): ..." for an empty ROI, an index out
  // of range, a duplicate, an empty handle, a handle vertex outside the ROI or in two
  // handles, and an ROI covering the whole mesh without any handle; and, for a method that
  // measures angles (needs_face_shapes()), a free vertex without a non-degenerate face.
  void precompute();

  // Deformed positions (#V by 3) for this frame. Throws InvalidArgument when the transform
  // counts differ from the handle counts or a transform is not finite / not affine.
  Vertices deform(const HandleTransforms& transforms);

  const TriMesh& rest() const { return mesh_; }
  const Layout& layout() const { return layout_; }
  virtual std::string name() const = 0;

 protected:
  virtual void setup(const Layout& layout) = 0;
  // Whether the method measures the rest mesh's angles, normals or areas (cotangent weights,
  // gradients, rotations): then a free vertex whose faces are all degenerate
  // (geometry::kDegenerateTriangleHeight) or that has none cannot be placed, and precompute()
  // says so instead of failing inside the solver. Uniform naive editing does not.
  virtual bool needs_face_shapes() const { return true; }
  // Subclasses call this when an option that setup() depends on changes.
  void mark_dirty() { dirty_ = true; }
  // targets  #V by 3: rest positions moved by the handle transforms at handle vertices, rest
  // positions elsewhere. out  #V by 3, prefilled with targets.
  virtual void solve(const HandleTransforms& transforms, const Vertices& targets, Vertices& out) = 0;

  TriMesh mesh_;

 private:
  Selection selection_;
  Layout layout_;
  bool dirty_ = true;
};

// Layout of `selection` on a mesh with num_vertices vertices; throws like precompute().
Layout make_layout(const Selection& selection, int num_vertices, const char* context);

// Applies the affine 4x4 T to p.
inline Eigen::Vector3d apply(const Eigen::Matrix4d& T, const Eigen::Vector3d& p) {
  return T.topLeftCorner<3, 3>() * p + T.topRightCorner<3, 1>();
}

}  // namespace lapis::mesh_deform
