#include "lapis/viewer/scene.h"

#include <limits>

namespace lapis::viewer {
namespace {

// FNV-1a over raw bytes, 64 bits: two different scenes hashing alike is vanishingly unlikely.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  template <class T>
  void add(const T& value) {
    bytes(&value, sizeof value);
  }
  void add(const std::string& s) {
    add(s.size());
    bytes(s.data(), s.size());
  }
  template <class Derived>
  void add_matrix(const Eigen::MatrixBase<Derived>& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) add(m.derived().data()[i]);
  }
};

}  // namespace

std::uint64_t camera_signature(const geometry::CameraMatrices& camera, int width, int height) {
  Hash h;
  h.add(width), h.add(height);
  h.add_matrix(camera.view), h.add_matrix(camera.projection);
  return h.h;
}

std::uint64_t scene_signature(const Scene& scene, const geometry::CameraMatrices& camera, int width, int height) {
  Hash h;
  h.add(width), h.add(height);
  h.add_matrix(camera.view), h.add_matrix(camera.projection);
  h.add_matrix(scene.background);
  for (const auto& [name, m] : scene.meshes) {
    h.add(name), h.add(m.version), h.add(m.visible), h.add(m.alpha);
    h.add_matrix(m.base_color);
  }
  for (const auto& [name, l] : scene.lines) {
    h.add(name), h.add(l.version), h.add(l.visible), h.add(l.alpha), h.add(l.width), h.add(l.tip_width),
        h.add(l.shading), h.add(l.on_top);
    h.add_matrix(l.base_color);
  }
  for (const auto& [name, p] : scene.points) {
    h.add(name), h.add(p.version), h.add(p.visible), h.add(p.size), h.add(p.on_top);
    h.add_matrix(p.base_color);
  }
  return h.h;
}

void LineItem::add_strip(const std::vector<Eigen::Vector3f>& strip) {
  const Eigen::Index old = points.rows();
  points.conservativeResize(old + static_cast<Eigen::Index>(strip.size()), 3);
  for (size_t k = 0; k < strip.size(); ++k) points.row(old + static_cast<Eigen::Index>(k)) = strip[k].transpose();
  strip_offsets.push_back(static_cast<int>(points.rows()));
  ++version;
}

void LineItem::add_strip(const std::vector<Eigen::Vector3d>& strip, const Eigen::Vector3f& color) {
  const Eigen::Index old = points.rows();
  if (colors.rows() != old) colors = base_color.transpose().replicate(old, 1);
  points.conservativeResize(old + static_cast<Eigen::Index>(strip.size()), 3);
  colors.conservativeResize(points.rows(), 3);
  for (size_t k = 0; k < strip.size(); ++k) {
    points.row(old + static_cast<Eigen::Index>(k)) = strip[k].cast<float>().transpose();
    colors.row(old + static_cast<Eigen::Index>(k)) = color.transpose();
  }
  strip_offsets.push_back(static_cast<int>(points.rows()));
  ++version;
}

void LineItem::clear() {
  points.resize(0, 3);
  colors.resize(0, 3);
  light.clear();
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
