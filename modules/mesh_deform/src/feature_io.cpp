#include "lapis/mesh_deform/feature_io.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lapis/core/atomic_file.h"
#include "lapis/core/checked_number.h"

namespace lapis::mesh_deform {
namespace {

using nlohmann::json;

// RGB in [0, 1] of s on [lo, hi]: blue, cyan, green, yellow, red (a file viewer's legend-free map).
Eigen::Vector3d saliency_color(double s, double lo, double hi) {
  const double t = hi > lo ? std::clamp((s - lo) / (hi - lo), 0.0, 1.0) : 0.5;
  static const Eigen::Vector3d stops[5] = {{0, 0, 1}, {0, 1, 1}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}};
  const double x = t * 4;
  const int k = std::min(3, static_cast<int>(x));
  return stops[k] + (x - k) * (stops[k + 1] - stops[k]);
}

}  // namespace

std::vector<Feature> read_features(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot open features file '" + path.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  json j;
  try {
    j = json::parse(ss.str());
  } catch (const json::exception& e) {
    throw IoError(path.string() + ": " + e.what());
  }
  if (!j.is_object() || !j.contains("features") || !j["features"].is_array())
    throw IoError(path.string() + ": expected {\"features\": [[vertex indices], ...]}");
  std::vector<Feature> out;
  for (size_t f = 0; f < j["features"].size(); ++f) {
    const json& a = j["features"][f];
    const std::string where = path.string() + ": feature " + std::to_string(f);
    if (!a.is_array()) throw IoError(where + ": expected an array of vertex indices, found " + a.type_name());
    Feature g;
    for (size_t k = 0; k < a.size(); ++k) g.push_back(json_index<IoError>(a[k], where + " entry " + std::to_string(k)));
    out.push_back(std::move(g));
  }
  return out;
}

void write_features(const std::filesystem::path& path, const std::vector<Feature>& features) {
  json j = {{"features", json::array()}};
  for (const Feature& f : features) j["features"].push_back(f);
  core::write_file_atomically(path, [&](std::ostream& out) { out << j.dump() << "\n"; });
}

void write_saliency_ply(const std::filesystem::path& path, const geometry::TriMesh& mesh,
                        const Eigen::VectorXd& saliency, const std::vector<Feature>& features) {
  if (saliency.size() != mesh.num_vertices())
    throw InvalidArgument("mesh_deform::write_saliency_ply(): " + std::to_string(saliency.size()) +
                          " saliency values for " + std::to_string(mesh.num_vertices()) + " vertices");
  std::vector<char> in_feature(static_cast<size_t>(mesh.num_vertices()), 0);
  for (const Feature& f : features)
    for (int v : f)
      if (v >= 0 && v < mesh.num_vertices()) in_feature[static_cast<size_t>(v)] = 1;
  const double lo = saliency.minCoeff(), hi = saliency.maxCoeff();
  core::write_file_atomically(path, [&](std::ostream& out) {
    out << "ply\nformat ascii 1.0\nelement vertex " << mesh.num_vertices()
        << "\nproperty double x\nproperty double y\nproperty double z\n"
           "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face "
        << mesh.num_faces() << "\nproperty list uchar int vertex_indices\nend_header\n";
    out.precision(17);
    for (int i = 0; i < mesh.num_vertices(); ++i) {
      Eigen::Vector3d c = saliency_color(saliency[i], lo, hi);
      if (in_feature[static_cast<size_t>(i)]) c = 0.5 * (c + Eigen::Vector3d::Ones());
      out << mesh.V(i, 0) << ' ' << mesh.V(i, 1) << ' ' << mesh.V(i, 2);
      for (int k = 0; k < 3; ++k) out << ' ' << static_cast<int>(std::lround(255 * c[k]));
      out << '\n';
    }
    for (int f = 0; f < mesh.num_faces(); ++f)
      out << "3 " << mesh.F(f, 0) << ' ' << mesh.F(f, 1) << ' ' << mesh.F(f, 2) << '\n';
  });
}

}  // namespace lapis::mesh_deform
