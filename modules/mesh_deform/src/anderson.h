// Private: Anderson acceleration of a fixed-point iteration x ← g(x) (type II, as Peng et al.
// 2018 apply it to local/global geometry solvers). Iterative Laplacian editing (Eq. 3, and the
// isoline model's Eq. 6 / Eq. 10) is such an iteration and converges linearly; on a mesh with
// free protrusions (armadillo) its rate is ~0.93, 35–50 iterations for a frame. Mixing the
// last few iterates cuts that several times for a least-squares problem of `depth` unknowns.
#pragma once

#include <deque>

#include <Eigen/Dense>

namespace lapis::mesh_deform::detail {

class Anderson {
 public:
  explicit Anderson(int depth) : depth_(depth) {}
  void reset() { df_.clear(), dg_.clear(), have_last_ = false; }

  // The next iterate from x and g = g(x); with depth 0, g itself.
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
    const Eigen::VectorXd f = g - x;
    if (depth_ <= 0) return g;
    // A residual that grows (a strongly nonlinear step) voids the history: restart from g.
    if (have_last_ && f.norm() > last_f_.norm()) reset();
    if (have_last_) {
      df_.push_back(f - last_f_);
      dg_.push_back(g - last_g_);
      if (static_cast<int>(df_.size()) > depth_) df_.pop_front(), dg_.pop_front();
    }
    last_f_ = f, last_g_ = g, have_last_ = true;
    if (df_.empty()) return g;
    Eigen::MatrixXd DF(f.size(), df_.size()), DG(f.size(), dg_.size());
    for (size_t k = 0; k < df_.size(); ++k) DF.col(k) = df_[k], DG.col(k) = dg_[k];
    const Eigen::VectorXd gamma = DF.colPivHouseholderQr().solve(f);
    if (!gamma.allFinite()) return reset(), g;
    return g - DG * gamma;
  }

 private:
  int depth_;
  std::deque<Eigen::VectorXd> df_, dg_;
  Eigen::VectorXd last_f_, last_g_;
  bool have_last_ = false;
};

}  // namespace lapis::mesh_deform::detail
