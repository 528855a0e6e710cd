// Private: the cell matrices A = Σ ω e′ eᵀ of every edge node from per-vertex sums. An edge
// node's cell is two fans, one per end (Wang et al. §3.3, Fig. 3), and the fan at end i of
// edge (i, j) is Σ_k u_ik (x_j − x_k)(v_j − v_k)ᵀ over i's neighbours k (the k = j term is 0):
// expanded, a few products of x_j, v_j with sums over i's ring that all edges at i share. A
// node then costs four outer products instead of ten gathered ones, and each iteration's
// vertex sums cost one pass over the rings. Coordinates are taken relative to the fan's
// centre i, so the expansion cancels nothing larger than the ring.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform::detail {

struct Stencil;

class EdgeCellSums {
 public:
  // s  the vertex stencil; u  per stencil entry the fan weight u_ik ≥ 0; rest  #V by 3.
  EdgeCellSums(const Stencil& s, std::vector<double> u, const geometry::Vertices& rest);
  // The ring sums of the deformed positions X (#V by 3), over every vertex, in parallel.
  void update(const geometry::Vertices& X);
  // Σ over both fans of edge (i, j) of u (x_a − x_k)(v_a − v_k)ᵀ, a the far end: the cell
  // matrix A of the node before its factor ω c².
  Eigen::Matrix3d fans(int i, int j, const geometry::Vertices& X) const;

 private:
  Eigen::Matrix3d fan(int centre, int end, const geometry::Vertices& X) const;
  const Stencil& s_;
  std::vector<double> u_;
  const geometry::Vertices& rest_;
  std::vector<double> weight_;             // per vertex: Σ_k u_ik
  std::vector<Eigen::Vector3d> rest_sum_;  // per vertex: Σ_k u_ik (v_k − v_i)
  std::vector<Eigen::Vector3d> sum_;       // per vertex: Σ_k u_ik (x_k − x_i)
  std::vector<Eigen::Matrix3d> outer_;     // per vertex: Σ_k u_ik (x_k − x_i)(v_k − v_i)ᵀ
};

}  // namespace lapis::mesh_deform::detail
