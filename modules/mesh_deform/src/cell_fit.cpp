#include "cell_fit.h"

#include <Eigen/Eigenvalues>

#include "rotation_fit.h"

namespace lapis::mesh_deform::detail {
namespace {

// Per-axis least-squares scales S_a = num_a / den_a (the zero of ∂E/∂S_a, §3.4), pooled over
// axes of one group. An axis the cell does not span (den ≈ 0: a flat vertex cell's normal)
// takes the fallback, the cell's isotropic scale: δ has no component there either, and a
// similarity then stays a fixed point.
// fallback() is called only for such an axis (rare: it costs a 3x3 product).
template <class Fallback>
Eigen::Vector3d axis_scales(const Eigen::Vector3d& num, const Eigen::Vector3d& den, const Eigen::Vector3i& group,
                            double spread, Fallback fallback) {
  Eigen::Vector3d s;
  for (int a = 0; a < 3; ++a) {
    double n = 0, d = 0;
    for (int b = 0; b < 3; ++b)
      if (group[b] == group[a]) n += num[b], d += den[b];
    s[a] = d > 1e-12 * spread ? n / d : fallback();
  }
  return s;
}

// s = Σ ω (R1 e)ᵀ e′ / Σ ω ‖e‖² = tr(R1ᵀ A) / tr(C0); 1 for an empty or inverted cell.
double isotropic_scale(const Eigen::Matrix3d& A, const Eigen::Matrix3d& R1, double spread) {
  const double num = (R1.transpose() * A).trace();
  return spread > 0 && num > 0 ? num / spread : 1.0;
}

}  // namespace

RestCell rest_cell(const Eigen::Matrix3d& C0, bool principal) {
  RestCell r;
  r.C0 = C0;
  if (!principal) return r;
  // The iterative solver, not computeDirect: its eigenvectors turn with the cell to rounding,
  // which the frame-independence of RestPrincipal rests on.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C0);
  r.U = es.eigenvectors();
  r.lambda = es.eigenvalues();
  const double tol = kEqualEigenvalues * std::max(r.lambda[2], 0.0);
  r.group[0] = 0;
  r.group[1] = r.lambda[1] - r.lambda[0] <= tol ? r.group[0] : 1;
  r.group[2] = r.lambda[2] - r.lambda[1] <= tol ? r.group[1] : 2;
  return r;
}

bool fit_cell(const Eigen::Matrix3d& A, const RestCell& rest, CellTransform transform, ScaleFrame frame,
              CellState& st) {
  bool fell_back = false;
  // R1 = argmax tr(Rᵀ A) (Sorkine & Alexa), warm-started from the node's last R1.
  const Eigen::Matrix3d R1 = nearest_rotation(A, st.q1, &fell_back);
  const double spread = rest.C0.trace();
  switch (transform) {
    case CellTransform::Rotation:
      st.T = R1;
      return fell_back;
    case CellTransform::IsotropicScale: {
      st.T = isotropic_scale(A, R1, spread) * R1;
      return fell_back;
    }
    case CellTransform::AnisotropicScale:
    case CellTransform::Full:
      break;
  }
  if (frame == ScaleFrame::World) {
    // §3.4 with f = R1 e: S_a = Σ ω f_a e′_a / Σ ω f_a² = (R1 Aᵀ)_aa / (R1 C0 R1ᵀ)_aa.
    // (Only the diagonals are formed: row a of R1 against row a of A, and of R1 C0.)
    const Eigen::Vector3d num = R1.cwiseProduct(A).rowwise().sum();
    const Eigen::Vector3d den = (R1 * rest.C0).cwiseProduct(R1).rowwise().sum();
    st.T = axis_scales(num, den, Eigen::Vector3i(0, 1, 2), spread, [&] { return isotropic_scale(A, R1, spread); })
               .asDiagonal() *
           R1;
  } else {
    // T = R1 U S Uᵀ, g = Uᵀ e, h = Uᵀ R1ᵀ e′: S_a = Σ ω g_a h_a / Σ ω g_a² = (Uᵀ Aᵀ R1 U)_aa / λ_a.
    const Eigen::Vector3d num = (rest.U.transpose() * A.transpose() * R1 * rest.U).diagonal();
    const Eigen::Vector3d S =
        axis_scales(num, rest.lambda, rest.group, spread, [&] { return isotropic_scale(A, R1, spread); });
    st.T = R1 * rest.U * S.asDiagonal() * rest.U.transpose();
  }
  if (transform == CellTransform::Full) {
    // Eq. 8's R2 with S R1 held: argmin Σ ω ‖e′ − R2 (T e)‖², the rotation of A Tᵀ.
    bool fb2 = false;
    st.T = nearest_rotation(A * st.T.transpose(), st.q2, &fb2) * st.T;
    fell_back = fell_back || fb2;
  }
  return fell_back;
}

}  // namespace lapis::mesh_deform::detail
