#include "uv_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lapis::mesh_merge::detail {
namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

UvLocator::UvLocator(const Eigen::MatrixX2d& uv, const geometry::Faces& F) : uv_(uv), F_(F) {
  const int nf = static_cast<int>(F.rows());
  g_ = std::max(1, static_cast<int>(std::ceil(std::sqrt(double(nf)))));
  lo_ = uv.rows() ? Eigen::Vector2d(uv.colwise().minCoeff().transpose()) : Eigen::Vector2d::Zero();
  const Eigen::Vector2d hi = uv.rows() ? Eigen::Vector2d(uv.colwise().maxCoeff().transpose()) : lo_;
  size_ = (hi - lo_).cwiseMax(1e-300);
  cells_.resize(static_cast<size_t>(g_) * g_);
  for (int f = 0; f < nf; ++f) {
    Eigen::Vector2d a = uv.row(F(f, 0)), b = a;
    for (int j = 1; j < 3; ++j)
      a = a.cwiseMin(uv.row(F(f, j)).transpose()), b = b.cwiseMax(uv.row(F(f, j)).transpose());
    for (int y = cell(a.y(), 1); y <= cell(b.y(), 1); ++y)
      for (int x = cell(a.x(), 0); x <= cell(b.x(), 0); ++x) cells_[static_cast<size_t>(y) * g_ + x].push_back(f);
  }
}

int UvLocator::cell(double x, int axis) const {
  const double t = (x - lo_(axis)) / size_(axis);
  if (!(t > 0)) return 0;  // also NaN
  return std::min(static_cast<int>(t * g_), g_ - 1);
}

bool UvLocator::barycentric(int f, const Eigen::Vector2d& q, Eigen::Vector3d& w) const {
  const Eigen::Vector2d a = uv_.row(F_(f, 0)), b = uv_.row(F_(f, 1)), c = uv_.row(F_(f, 2));
  const double det = cross(b - a, c - a);
  if (!(std::abs(det) > 1e-14 * (b - a).squaredNorm())) return false;
  w(1) = cross(q - a, c - a) / det;
  w(2) = cross(b - a, q - a) / det;
  w(0) = 1 - w(1) - w(2);
  return true;
}

UvHit UvLocator::locate_in_cell(const Eigen::Vector2d& q) const {
  UvHit hit;
  hit.min_weight = -std::numeric_limits<double>::infinity();
  Eigen::Vector3d w;
  for (int f : cells_[static_cast<size_t>(cell(q.y(), 1)) * g_ + cell(q.x(), 0)])
    if (barycentric(f, q, w) && w.minCoeff() > hit.min_weight) hit = {f, w, w.minCoeff()};
  return hit;
}

UvHit UvLocator::locate(const Eigen::Vector2d& q) const {
  UvHit hit = locate_in_cell(q);
  if (hit.min_weight >= -1e-9) return hit;
  Eigen::Vector3d w;
  for (int f = 0; f < static_cast<int>(F_.rows()); ++f)
    if (barycentric(f, q, w) && w.minCoeff() > hit.min_weight) hit = {f, w, w.minCoeff()};
  return hit;
}

}  // namespace lapis::mesh_merge::detail
