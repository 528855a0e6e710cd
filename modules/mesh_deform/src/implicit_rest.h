// Private: the rest-state geometry of implicit Laplacian editing. Makes every deformation
// gradient M_i well defined (thesis §2.4.3: midpoints inserted at boundary vertices of valence
// < 3, degenerate vertices displaced along the normal, Eq. 2.9) and expresses each M_i as a
// linear function of the unknown positions (Eq. 2.3–2.5).
#pragma once

#include <array>
#include <vector>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "stencil.h"

namespace lapis::mesh_deform::detail {

// The mesh the implicit method solves on: the rest mesh plus inserted midpoints (appended
// after the #V original vertices, dropped from the output), with extended vertex roles.
struct WorkMesh {
  TriMesh mesh;
  std::vector<std::array<int, 2>> inserted;  // edge endpoints of midpoint #V + k
  std::vector<VertexRole> role;
  std::vector<int> handle_of;
  std::vector<char> active;  // M_i is used: within 2 rings of a free vertex
  Vertices displaced;        // positions with degenerate vertices displaced (v'_i of Eq. 2.9)
  std::vector<int> moved;    // vertices whose displaced position differs from the rest one
  int degenerate = 0;        // vertices found degenerate (§2.4.3)
  Stencil stencil;           // mesh's 1-rings (uniform weights): reweight() a copy for others
};

WorkMesh build_work_mesh(const TriMesh& rest, const Layout& layout, const ImplicitOptions& options);

// M_i = Σ_k ṽ_k g_kᵀ over k ∈ {i} ∪ N(i) (Eq. 2.5 with the translation eliminated, Eq. 2.4):
// row a of M_i is linear in coordinate a of the unknowns only, which is why x, y, z are
// separate right-hand sides of one matrix (§2.5). CSR over vertices; empty for inactive ones.
struct GradientStencils {
  std::vector<int> offsets;
  std::vector<int> vertex;
  std::vector<Eigen::Vector3d> g;
  // M_i from positions X (#V' by 3).
  Eigen::Matrix3d gradient(int i, const Vertices& X) const {
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
    for (int k = offsets[i]; k < offsets[i + 1]; ++k) M.noalias() += X.row(vertex[k]).transpose() * g[k].transpose();
    return M;
  }
};

// Stencils at the active vertices of positions P (the displaced ones). A vertex that stays
// degenerate after displacement (it cannot happen on a manifold mesh, but input is input)
// gets a Tikhonov-regularized inverse so the system stays defined.
GradientStencils gradient_stencils(const Stencil& s, const Vertices& P, const std::vector<char>& active);

// Thesis §3.5: every active vertex of a group takes the group's one deformation gradient,
// implicitly defined like a 1-ring's (Eq. 2.3–2.5) but over the group: the least-squares linear
// map from the rest group about its centroid to the deformed one, M_F = Σ_j ṽ_j g_jᵀ with
// g_j = (Σ p pᵀ)⁻¹ (p_j − c). Fitted on at most kSharedAnchors of the group's vertices, spread
// by farthest-point sampling, so each of the group's rows holds that many unknowns (the
// normal matrix a dense block of their size) however large the group. 32 fit a near-similar
// motion as well as 128 did, for a fifth of the normal matrices' time (docs/decisions.md).
constexpr int kSharedAnchors = 32;
void share_gradients(GradientStencils& G, const Vertices& P, const std::vector<std::vector<int>>& groups,
                     const std::vector<char>& active);

// λ_max / λ_min of V_i V_iᵀ (Eq. 2.5), +inf when singular.
double stencil_condition(const Stencil& s, const Vertices& P, int i);

}  // namespace lapis::mesh_deform::detail
