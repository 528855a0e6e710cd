// Bounding volume hierarchy over a mesh's triangles: first-hit ray casting (stroke depth on
// the scalp, picking in the apps), closest points and inside tests (scalp penetration).
// Built once per mesh with binned SAH (Wald 2007), in parallel with OpenMP tasks.
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

struct RayHit {
  int face = -1;
  double t = 0;                 // hit point = origin + t * direction
  Eigen::Vector3d barycentric;  // weights of the face's corners 0, 1, 2
  Eigen::Vector3d point;
};

struct ClosestPoint {
  int face = -1;
  double distance = 0;
  Eigen::Vector3d barycentric;
  Eigen::Vector3d point;
};

struct BvhOptions {
  int max_leaf_size = 4;       // triangles per leaf at most (a common choice for SAH trees)
  int bins = 16;               // SAH bins per split, 2..64 (Wald 2007 reports 16 as enough)
  int parallel_cutoff = 8192;  // subtrees smaller than this are built by one task
};

class Bvh {
 public:
  // Copies the mesh. Throws InvalidArgument for out-of-range indices or non-finite vertices.
  explicit Bvh(const TriMesh& mesh, const BvhOptions& options = {});

  // Nearest hit with t in [0, t_max] (Moller-Trumbore; direction need not be unit). Ties
  // go to the lower face index, so results do not depend on the tree's layout.
  std::optional<RayHit> intersect(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                                  double t_max = std::numeric_limits<double>::infinity()) const;

  // Closest point on the surface. Throws InvalidArgument on an empty mesh, a non-finite p or
  // one so far away (beyond 1e154) that squared distances overflow.
  ClosestPoint closest_point(const Eigen::Vector3d& p) const;

  // For closed meshes: whether p is inside, by the majority of three ray-crossing parities
  // along fixed, generic directions (robust to a ray grazing an edge).
  bool inside(const Eigen::Vector3d& p) const;

  int num_nodes() const { return static_cast<int>(nodes_.size()); }
  int depth() const;

 private:
  struct Node {
    double lo[3], hi[3];
    int first;  // leaf: first entry in order_; interior: index of the left child (right = first + 1)
    int count;  // triangles in the leaf; 0 for interior nodes
  };
  friend struct BvhBuilder;
  int count_crossings(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

  TriMesh mesh_;
  BvhOptions options_;
  std::vector<Node> nodes_;
  std::vector<int> order_;  // leaf ranges index this permutation of the faces
};

// Ray-triangle test shared by the tree and by brute-force checks: t and barycentrics of the
// hit of origin + t direction with triangle (a, b, c), or nothing (parallel, outside, t < 0).
std::optional<std::pair<double, Eigen::Vector3d>> intersect_triangle(const Eigen::Vector3d& origin,
                                                                     const Eigen::Vector3d& direction,
                                                                     const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                                                     const Eigen::Vector3d& c);

// Closest point on triangle (a, b, c) to p, as barycentric weights (Ericson, Real-Time
// Collision Detection, 5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

}  // namespace lapis::geometry
