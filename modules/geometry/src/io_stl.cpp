// STL, ASCII ("solid ... facet normal ... outer loop vertex x y z ... endsolid") and binary
// (80-byte header, uint32 count, 50 bytes per triangle, little endian). Corners with
// bitwise-equal positions become one vertex, which restores connectivity.
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "io_text.h"
#include "lapis/geometry/io.h"
#include "mesh_builder.h"

namespace lapis::geometry {
namespace {

constexpr const char* kRead = "geometry::read_stl()";

// Gives each distinct position one index.
class Welder {
 public:
  explicit Welder(size_t triangles) {
    index_.reserve(triangles / 2 + 1);
    mesh_.reserve(triangles / 2, triangles);
  }
  int corner(double x, double y, double z) {
    const Key k{x + 0.0, y + 0.0, z + 0.0};  // + 0.0 folds -0 into 0
    const auto [it, added] = index_.try_emplace(k, mesh_.num_vertices());
    if (added) mesh_.add_vertex(x, y, z);
    return it->second;
  }
  detail::MeshBuilder& mesh() { return mesh_; }

 private:
  struct Key {
    double x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    size_t operator()(const Key& k) const {
      size_t h = std::bit_cast<std::uint64_t>(k.x);
      h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<std::uint64_t>(k.y);
      h = h * 0x9E3779B97F4A7C15ull ^ std::bit_cast<std::uint64_t>(k.z);
      return h ^ (h >> 29);
    }
  };
  std::unordered_map<Key, int, Hash> index_;
  detail::MeshBuilder mesh_;
};

TriMesh read_binary(const std::string& data, const std::filesystem::path& path, Warnings* warnings) {
  std::uint32_t n = 0;
  std::memcpy(&n, data.data() + 80, 4);
  if constexpr (std::endian::native == std::endian::big) n = __builtin_bswap32(n);
  Welder weld(n);
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* rec = data.data() + 84 + 50 * static_cast<size_t>(t) + 12;  // skip the normal
    int corners[3];
    for (int c = 0; c < 3; ++c) {
      float p[3];
      std::memcpy(p, rec + 12 * c, 12);
      for (float& v : p) {
        if constexpr (std::endian::native == std::endian::big)
          v = std::bit_cast<float>(__builtin_bswap32(std::bit_cast<std::uint32_t>(v)));
        if (!std::isfinite(v))
          detail::io_fail(kRead, path, "byte " + std::to_string(84 + 50 * static_cast<size_t>(t) + 12 + 12 * c),
                          "non-finite coordinate in triangle " + std::to_string(t));
      }
      corners[c] = weld.corner(p[0], p[1], p[2]);
    }
    weld.mesh().add_polygon(corners);
  }
  return weld.mesh().finish(kRead, path, warnings);
}

TriMesh read_ascii(const std::string& data, const std::filesystem::path& path, Warnings* warnings) {
  detail::require_text(data, kRead, path);
  detail::TextCursor in(data, kRead, path, '\0');
  in.token();                      // "solid"
  in.rest_of_line();               // its name
  Welder weld(data.size() / 200);  // an ASCII facet takes ~250 bytes
  for (;;) {
    const std::string_view t = in.token();
    if (t == "endsolid") break;
    if (t.empty()) in.fail("file ends early, expected 'facet' or 'endsolid'");
    if (t != "facet") in.fail("expected 'facet' or 'endsolid', found " + detail::quote(t));
    if (in.token() != "normal") in.fail("expected 'normal' after 'facet'");
    for (int k = 0; k < 3; ++k) in.number("normal component");
    if (in.token() != "outer" || in.token() != "loop") in.fail("expected 'outer loop'");
    int corners[3];
    for (int c = 0; c < 3; ++c) {
      const std::string_view v = in.token();
      if (v != "vertex") in.fail("expected 'vertex' (a facet has 3), found " + detail::quote(v));
      const double x = in.number("vertex x coordinate");
      const double y = in.number("vertex y coordinate");
      const double z = in.number("vertex z coordinate");
      corners[c] = weld.corner(x, y, z);
    }
    const std::string_view e = in.token();
    if (e != "endloop") in.fail("expected 'endloop' after 3 vertices, found " + detail::quote(e));
    if (in.token() != "endfacet") in.fail("expected 'endfacet'");
    weld.mesh().add_polygon(corners);
  }
  return weld.mesh().finish(kRead, path, warnings);
}

}  // namespace

TriMesh read_stl(const std::filesystem::path& path, Warnings* warnings) {
  const std::string data = detail::read_file(path, kRead);
  if (data.empty()) detail::io_fail(kRead, path, "", "empty file, expected 'solid' or an 84-byte binary STL header");
  const bool says_solid = data.compare(0, 5, "solid") == 0;
  std::uint32_t n = 0;
  if (data.size() >= 84) {
    std::memcpy(&n, data.data() + 80, 4);
    if constexpr (std::endian::native == std::endian::big) n = __builtin_bswap32(n);
  }
  const unsigned long long binary_size = 84ull + 50ull * n;
  if (data.size() >= 84 && data.size() == binary_size) return read_binary(data, path, warnings);
  // Binary files often start with "solid" too: only text with a facet keyword is ASCII.
  if (says_solid && data.find("facet", 0) != std::string::npos && data.find('\0') == std::string::npos)
    return read_ascii(data, path, warnings);
  if (says_solid && data.size() < 84) return read_ascii(data, path, warnings);
  if (data.size() < 84)
    detail::io_fail(kRead, path, "byte " + std::to_string(data.size()),
                    "file ends inside the 84-byte binary STL header and is not ASCII STL");
  detail::io_fail(kRead, path, "byte 80",
                  "binary STL header claims " + std::to_string(n) + " triangles (" + std::to_string(binary_size) +
                      " bytes), but the file has " + std::to_string(data.size()) + " bytes");
}

void write_stl(const std::filesystem::path& path, const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::write_stl()");
  require_finite_vertices(mesh, "geometry::write_stl()");
  core::write_file_atomically(path, [&](std::ostream& out) {
    std::string s(80, '\0');
    s.replace(0, 22, "binary STL from Lapis ");
    auto put32 = [&](std::uint32_t v) {
      if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
      s.append(reinterpret_cast<const char*>(&v), 4);
    };
    auto putf = [&](double v) { put32(std::bit_cast<std::uint32_t>(static_cast<float>(v))); };
    put32(static_cast<std::uint32_t>(mesh.num_faces()));
    for (int f = 0; f < mesh.num_faces(); ++f) {
      const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
      for (int k = 0; k < 3; ++k) putf(std::isfinite(n[k]) ? n[k] : 0.0);
      for (const Eigen::Vector3d* p : {&a, &b, &c})
        for (int k = 0; k < 3; ++k) putf((*p)[k]);
      s.append(2, '\0');  // attribute byte count
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    out << s;
  });
}

}  // namespace lapis::geometry
