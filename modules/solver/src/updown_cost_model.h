// Private: predicts the milliseconds of a rank-k update/downdate and of a numeric
// refactorization, calibrated by timing the real operations as they run.
//
// A rank-1 update starting at permuted column k touches the columns of L on the
// elimination-tree path from k to the root (Davis & Hager 1999), so its cost is
// proportional to the entries along that path; the constant (ms per entry) is measured.
// A refactorization costs what the last one cost.
#pragma once

#include <vector>

namespace lapis::solver::detail {

class UpdownCostModel {
 public:
  // path_work[k]: entries of L on the path from permuted column k to the root.
  void reset(std::vector<double> path_work, double refactor_ms) {
    path_work_ = std::move(path_work);
    refactor_ms_ = refactor_ms;
    ms_per_entry_ = 0;
  }
  // A new analysis (new ordering) keeps the calibration.
  void set_paths(std::vector<double> path_work) { path_work_ = std::move(path_work); }
  bool calibrated() const { return ms_per_entry_ > 0; }

  // Work of modifying with columns whose first permuted row indices are `first_rows`.
  double work(const std::vector<int>& first_rows) const {
    double w = 0;
    for (int k : first_rows) w += path_work_[static_cast<size_t>(k)];
    return w;
  }
  double predict_updown_ms(double work) const { return work * ms_per_entry_; }
  double predict_refactor_ms() const { return refactor_ms_; }

  // Exponential averages: recent measurements dominate, one outlier does not.
  void observe_updown(double work, double ms) {
    if (work <= 0) return;
    const double sample = ms / work;
    ms_per_entry_ = calibrated() ? 0.5 * ms_per_entry_ + 0.5 * sample : sample;
  }
  void observe_refactor(double ms) { refactor_ms_ = 0.5 * refactor_ms_ + 0.5 * ms; }

 private:
  std::vector<double> path_work_;
  double refactor_ms_ = 0;
  double ms_per_entry_ = 0;
};

}  // namespace lapis::solver::detail
