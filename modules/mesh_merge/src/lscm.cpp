#include "lapis/mesh_merge/lscm.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/solver/least_squares.h"

namespace lapis::mesh_merge {
namespace {

constexpr const char* kFn = "mesh_merge::lscm()";

// Two rows per face: the real and imaginary part of Σ_j W_j U_j / √(2 A) with U_j = u_j + i v_j
// and W_j = the opposite edge (p_{j+2} − p_{j+1}) as a complex number in the face's own frame
// (Lévy et al. §3.3). Unknowns [u_0..u_n-1, v_0..v_n-1]. Degenerate faces add no rows.
solver::SparseMatrix conformal_rows(const TriMesh& mesh, ConformalWeights weights) {
  const int n = mesh.num_vertices();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(12 * mesh.num_faces()));
  int row = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d p0 = mesh.V.row(mesh.F(f, 0)), p1 = mesh.V.row(mesh.F(f, 1)), p2 = mesh.V.row(mesh.F(f, 2));
    const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
    const double l1 = e1.norm(), twice_area = e1.cross(e2).norm();
    if (!(l1 > 0) || !(twice_area > 1e-14 * l1 * l1)) continue;
    // The face in its own frame: p0 at 0, p1 on the x axis, p2 above it.
    const Eigen::Vector2d q[3] = {{0, 0}, {l1, 0}, {e2.dot(e1) / l1, twice_area / l1}};
    const double w = weights == ConformalWeights::PerArea ? 1 / std::sqrt(twice_area) : 1.0;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector2d W = q[(j + 2) % 3] - q[(j + 1) % 3];
      const int u = mesh.F(f, j), v = u + n;
      t.emplace_back(row, u, w * W.x()), t.emplace_back(row, v, -w * W.y());
      t.emplace_back(row + 1, u, w * W.y()), t.emplace_back(row + 1, v, w * W.x());
    }
    row += 2;
  }
  solver::SparseMatrix A(row, 2 * n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

Eigen::MatrixX2d lscm(const TriMesh& mesh, std::array<int, 2> pins, std::array<Eigen::Vector2d, 2> at,
                      ConformalWeights weights) {
  const int n = mesh.num_vertices();
  for (int p : pins)
    if (p < 0 || p >= n)
      throw InvalidArgument(std::string(kFn) + ": pin " + std::to_string(p) + " is out of range [0, " +
                            std::to_string(n) + ")");
  if (pins[0] == pins[1]) throw InvalidArgument(std::string(kFn) + ": the two pins are the same vertex");
  if (!((at[0] - at[1]).norm() > 0))
    throw InvalidArgument(std::string(kFn) + ": the two pins must be held at different points");
  // A vertex on no face has no row; hold it at the pins' midpoint so the system stays definite.
  std::vector<char> used(static_cast<size_t>(n), 0);
  for (int k = 0; k < mesh.F.size(); ++k) used[mesh.F.data()[k]] = 1;
  std::vector<int> fixed;
  std::vector<Eigen::Vector2d> value;
  for (int v = 0; v < n; ++v) {
    const int pin = v == pins[0] ? 0 : v == pins[1] ? 1 : -1;
    if (pin >= 0 || !used[v]) fixed.push_back(v), value.push_back(pin >= 0 ? at[pin] : 0.5 * (at[0] + at[1]));
  }
  solver::LeastSquares system(2 * n);
  system.add_block(conformal_rows(mesh, weights), 1.0, "LSCM conformal energy");
  std::vector<int> fixed_uv = fixed;
  for (int v : fixed) fixed_uv.push_back(v + n);
  system.set_fixed(fixed_uv);
  system.precompute();
  solver::DenseMatrix values(static_cast<Eigen::Index>(fixed_uv.size()), 1);
  for (size_t k = 0; k < fixed.size(); ++k) values(k, 0) = value[k].x(), values(k + fixed.size(), 0) = value[k].y();
  const solver::DenseMatrix x = system.solve({solver::DenseMatrix()}, values, 1);
  Eigen::MatrixX2d uv(n, 2);
  uv.col(0) = x.col(0).head(n);
  uv.col(1) = x.col(0).tail(n);
  return uv;
}

std::array<int, 2> farthest_pair(const TriMesh& mesh, const std::vector<int>& loop) {
  if (loop.size() < 2) throw InvalidArgument("mesh_merge::farthest_pair(): the loop has fewer than two vertices");
  std::array<int, 2> best{loop[0], loop[1]};
  double far = -1;
  for (size_t i = 0; i < loop.size(); ++i)
    for (size_t j = i + 1; j < loop.size(); ++j) {
      const double d = (mesh.V.row(loop[i]) - mesh.V.row(loop[j])).squaredNorm();
      if (d > far * (1 + 1e-12)) far = d, best = {loop[i], loop[j]};
    }
  return best;
}

Eigen::MatrixX2d lscm_pinned_on_loop(const TriMesh& mesh, const std::vector<int>& loop, bool scale_to_area) {
  Eigen::MatrixX2d uv = lscm(mesh, farthest_pair(mesh, loop), {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)});
  if (!scale_to_area) return uv;
  double area = 0, uv_area = 0;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    area += 0.5 * (mesh.V.row(b) - mesh.V.row(a)).cross(mesh.V.row(c) - mesh.V.row(a)).norm();
    const Eigen::Vector2d x = uv.row(b) - uv.row(a), y = uv.row(c) - uv.row(a);
    uv_area += 0.5 * std::abs(x.x() * y.y() - x.y() * y.x());
  }
  if (uv_area > 0) uv *= std::sqrt(area / uv_area);
  return uv;
}

}  // namespace lapis::mesh_merge
