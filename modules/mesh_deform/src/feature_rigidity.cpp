#include "lapis/mesh_deform/feature_rigidity.h"

#include <cmath>
#include <string>

#include "lapis/geometry/polar.h"

namespace lapis::mesh_deform {
namespace {

void check(const geometry::Vertices& rest, const geometry::Vertices& deformed, const Feature& f, const char* fn) {
  if (f.empty()) throw InvalidArgument(std::string(fn) + ": the feature is empty");
  if (rest.rows() != deformed.rows())
    throw InvalidArgument(std::string(fn) + ": rest and deformed positions differ in count");
  for (int v : f)
    if (v < 0 || v >= rest.rows())
      throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " out of range");
}

Eigen::Vector3d centroid(const geometry::Vertices& P, const Feature& f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : f) c += P.row(v).transpose();
  return c / static_cast<double>(f.size());
}

}  // namespace

Eigen::Matrix3d kabsch_rotation(const geometry::Vertices& rest, const geometry::Vertices& deformed, const Feature& f) {
  check(rest, deformed, f, "mesh_deform::kabsch_rotation()");
  const Eigen::Vector3d c = centroid(rest, f), cd = centroid(deformed, f);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  for (int v : f) A += (deformed.row(v).transpose() - cd) * (rest.row(v).transpose() - c).transpose();
  return geometry::polar_rotation(A);
}

double feature_rigidity_residual(const geometry::Vertices& rest, const geometry::Vertices& deformed, const Feature& f) {
  check(rest, deformed, f, "mesh_deform::feature_rigidity_residual()");
  const Eigen::Matrix3d R = kabsch_rotation(rest, deformed, f);
  const Eigen::Vector3d c = centroid(rest, f), cd = centroid(deformed, f);
  Eigen::Vector3d lo = rest.row(f[0]).transpose(), hi = lo;
  double e = 0;
  for (int v : f) {
    const Eigen::Vector3d p = rest.row(v).transpose();
    e += ((deformed.row(v).transpose() - cd) - R * (p - c)).squaredNorm();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diameter = (hi - lo).norm();
  return diameter > 0 ? std::sqrt(e / static_cast<double>(f.size())) / diameter : 0.0;
}

}  // namespace lapis::mesh_deform
