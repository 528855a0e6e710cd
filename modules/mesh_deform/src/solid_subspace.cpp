#include "lapis/mesh_deform/solid_subspace.h"

#include <Eigen/Dense>
#include <array>
#include <cmath>

namespace lapis::mesh_deform {
namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

Eigen::Vector3d corner(const geometry::TetMesh& m, int t, int k) { return m.V.row(m.T(t, k)).transpose(); }

// ∇φ_a for the four corners of tet t, as columns.
Eigen::Matrix<double, 3, 4> barycentric_gradients(const geometry::TetMesh& m, int t) {
  Eigen::Matrix3d E;
  E << corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0), corner(m, t, 3) - corner(m, t, 0);
  const Eigen::Matrix3d Einv = E.inverse();  // row r: ∇φ_{r+1}
  Eigen::Matrix<double, 3, 4> g;
  g.rightCols<3>() = Einv.transpose();
  g.col(0) = -g.rightCols<3>().rowwise().sum();
  return g;
}

// Row l of one output coordinate's Jacobian at u in tet t, as coefficients of Z's column:
// ∂x/∂u_l = Σ_a (x_a + M_a·(u − u_a)) ∂_l φ_a + φ_a(u) M_{a,l}. Adds sign·weight·coefficients to row.
void add_jacobian_row(const geometry::TetMesh& m, int t, const Eigen::Vector3d& u, int l, double weight, int row,
                      Triplets& out) {
  const Eigen::Matrix<double, 3, 4> g = barycentric_gradients(m, t);
  const Eigen::Vector4d phi = geometry::tet_barycentric(m, t, u);
  for (int a = 0; a < 4; ++a) {
    const int col = 4 * m.T(t, a);
    const Eigen::Vector3d d = u - corner(m, t, a);
    out.emplace_back(row, col, weight * g(l, a));
    for (int q = 0; q < 3; ++q) out.emplace_back(row, col + 1 + q, weight * (d[q] * g(l, a) + (q == l ? phi[a] : 0)));
  }
}

}  // namespace

SubspaceEmbedding embed_in_subspace(const geometry::TetMesh& tets, const geometry::Vertices& P) {
  if (!P.allFinite()) throw InvalidArgument("mesh_deform::embed_in_subspace(): a surface vertex is not finite");
  const geometry::TetLocator locator(tets);
  SubspaceEmbedding e;
  const int n = static_cast<int>(P.rows());
  e.tet_of.resize(static_cast<size_t>(n));
  Triplets t;
  t.reserve(static_cast<size_t>(n) * 16);
  for (int j = 0; j < n; ++j) {
    const Eigen::Vector3d p = P.row(j).transpose();
    const geometry::TetLocation loc = locator.locate(p);
    e.tet_of[static_cast<size_t>(j)] = loc.tet;
    e.strays += !loc.inside;
    for (int a = 0; a < 4; ++a) {
      const int col = 4 * tets.T(loc.tet, a);
      const Eigen::Vector3d d = p - corner(tets, loc.tet, a);
      t.emplace_back(j, col, loc.barycentric[a]);
      for (int l = 0; l < 3; ++l) t.emplace_back(j, col + 1 + l, loc.barycentric[a] * d[l]);
    }
  }
  e.C.resize(n, 4 * tets.num_vertices());
  e.C.setFromTriplets(t.begin(), t.end());
  return e;
}

solver::DenseMatrix affine_coefficients(const geometry::TetMesh& tets, const Eigen::Matrix3d& G,
                                        const Eigen::Vector3d& t) {
  solver::DenseMatrix Z(4 * tets.num_vertices(), 3);
  for (int i = 0; i < tets.num_vertices(); ++i) {
    Z.row(4 * i) = (G * tets.V.row(i).transpose() + t).transpose();
    Z.block<3, 3>(4 * i + 1, 0) = G.transpose();  // row 4i+1+l, column k: (M_i)_{k,l}
  }
  return Z;
}

solver::DenseMatrix rest_coefficients(const geometry::TetMesh& tets) {
  return affine_coefficients(tets, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
}

solver::SparseMatrix discontinuity_rows(const geometry::TetMesh& tets) {
  Triplets out;
  int row = 0;
  for (const geometry::SharedFace& face : geometry::shared_faces(tets)) {
    const auto& f = face.corners;
    const auto& pair = face.tets;
    const Eigen::Vector3d a = tets.V.row(f[0]).transpose(), b = tets.V.row(f[1]).transpose(),
                          c = tets.V.row(f[2]).transpose();
    const double w = std::sqrt(0.5 * (b - a).cross(c - a).norm() / 3);
    for (const Eigen::Vector3d& u :
         {Eigen::Vector3d(0.5 * (a + b)), Eigen::Vector3d(0.5 * (b + c)), Eigen::Vector3d(0.5 * (c + a))})
      for (int l = 0; l < 3; ++l, ++row) {
        add_jacobian_row(tets, pair[0], u, l, w, row, out);
        add_jacobian_row(tets, pair[1], u, l, -w, row, out);
      }
  }
  solver::SparseMatrix B(row, 4 * tets.num_vertices());
  B.setFromTriplets(out.begin(), out.end());
  return B;
}

solver::SparseMatrix vibration_rows(const geometry::TetMesh& tets) {
  Triplets out;
  int row = 0;
  for (int t = 0; t < tets.num_tets(); ++t) {
    const Eigen::Matrix<double, 3, 4> g = barycentric_gradients(tets, t);
    const double vol =
        geometry::tet_volume(corner(tets, t, 0), corner(tets, t, 1), corner(tets, t, 2), corner(tets, t, 3));
    const double w = std::cbrt(vol);  // √(vol^{2/3})
    for (int i = 0; i < 4; ++i)
      for (int l = 0; l < 3; ++l, ++row) {
        out.emplace_back(row, 4 * tets.T(t, i) + 1 + l, w);
        for (int a = 0; a < 4; ++a) out.emplace_back(row, 4 * tets.T(t, a), -w * g(l, a));
      }
  }
  solver::SparseMatrix B(row, 4 * tets.num_vertices());
  B.setFromTriplets(out.begin(), out.end());
  return B;
}

}  // namespace lapis::mesh_deform
