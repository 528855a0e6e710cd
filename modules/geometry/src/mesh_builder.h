// Private: collects vertices and polygons while a reader parses, fan-triangulating polygons
// (and counting them for the reader's warning), then hands out a TriMesh.
#pragma once

#include <charconv>
#include <span>
#include <string>
#include <vector>

#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry::detail {

class MeshBuilder {
 public:
  void reserve(size_t vertices, size_t faces) {
    xyz_.reserve(3 * vertices);
    tri_.reserve(3 * faces);
  }
  void add_vertex(double x, double y, double z) { xyz_.insert(xyz_.end(), {x, y, z}); }
  int num_vertices() const { return static_cast<int>(xyz_.size() / 3); }
  // Indices must already be checked by the reader (it knows the line to blame).
  void add_polygon(std::span<const int> corners) {
    if (corners.size() > 3) ++polygons_;
    for (size_t k = 1; k + 1 < corners.size(); ++k) tri_.insert(tri_.end(), {corners[0], corners[k], corners[k + 1]});
  }
  // Appends "fan-triangulated N polygons ..." to warnings when any polygon had > 3 corners.
  TriMesh finish(const std::string& fn, const std::filesystem::path& path, Warnings* warnings) {
    if (warnings && polygons_ > 0)
      warnings->push_back(fn + ": " + path.string() + ": fan-triangulated " + std::to_string(polygons_) +
                          " polygons with more than 3 corners");
    TriMesh m;
    m.V = Eigen::Map<const Vertices>(xyz_.data(), static_cast<Eigen::Index>(xyz_.size() / 3), 3);
    m.F = Eigen::Map<const Faces>(tri_.data(), static_cast<Eigen::Index>(tri_.size() / 3), 3);
    return m;
  }

 private:
  std::vector<double> xyz_;
  std::vector<int> tri_;
  size_t polygons_ = 0;
};

// Shortest text that reads back to the same double.
inline void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}
inline void append_number(std::string& out, long long v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

}  // namespace lapis::geometry::detail
