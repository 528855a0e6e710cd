#include "lapis/viewer/scene.h"

#include <limits>

namespace lapis::viewer {

void LineItem::add_strip(const std::vector<Eigen::Vector3f>& strip) {
  const Eigen::Index old = points.rows();
  points.conservativeResize(old + static_cast<Eigen::Index>(strip.size()), 3);
  for (size_t k = 0; k < strip.size(); ++k) points.row(old + static_cast<Eigen::Index>(k)) = strip[k].transpose();
  strip_offsets.push_back(static_cast<int>(points.rows()));
  ++version;
}

void LineItem::clear() {
  points.resize(0, 3);
  colors.resize(0, 3);
  strip_offsets.assign(1, 0);
  ++version;
}

bool Scene::bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi = -lo;
  bool any = false;
  for (const auto& [name, item] : meshes) {
    if (!item.visible || item.mesh.V.rows() == 0) continue;
    lo = lo.cwiseMin(item.mesh.V.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(item.mesh.V.colwise().maxCoeff().transpose());
    any = true;
  }
  if (any) return true;
  for (const auto& [name, item] : lines) {
    if (!item.visible || item.points.rows() == 0) continue;
    lo = lo.cwiseMin(item.points.colwise().minCoeff().transpose().cast<double>());
    hi = hi.cwiseMax(item.points.colwise().maxCoeff().transpose().cast<double>());
    any = true;
  }
  return any;
}

}  // namespace lapis::viewer
