// Wavefront OBJ: 'v x y z [w] [r g b]', 'f' with 'i', 'i/t', 'i//n', 'i/t/n' corners (negative
// = relative to the last vertex), polygons fan-triangulated, 'l' polylines. Other known
// statements (vt, vn, g, o, s, usemtl, ...) are skipped; an unknown one is an error, which
// is how binary garbage and non-OBJ files are caught.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "io_text.h"
#include "lapis/geometry/io.h"
#include "mesh_builder.h"

namespace lapis::geometry {
namespace {

constexpr std::array<std::string_view, 38> kSkipped = {
    "vt",        "vn",    "vp",    "p",     "o",        "g",        "s",      "mg",     "usemtl", "mtllib",
    "cstype",    "deg",   "bmat",  "step",  "curv",     "curv2",    "surf",   "parm",   "trim",   "hole",
    "scrv",      "sp",    "end",   "con",   "call",     "csh",      "maplib", "usemap", "lod",    "shadow_obj",
    "trace_obj", "ctech", "stech", "bevel", "c_interp", "d_interp", "vc",     "#"};

struct ObjContent {
  detail::MeshBuilder mesh;
  std::vector<std::vector<int>> lines;
};

// One corner of an 'f' or 'l' statement: the vertex index before any '/'.
int corner_index(detail::TextCursor& in, std::string_view token, int num_vertices) {
  const std::string_view head = token.substr(0, token.find('/'));
  long long i = 0;
  if (!detail::parse_int(head, i) || i == 0)
    in.fail("expected a vertex index (1-based or negative), found " + detail::quote(token));
  const long long zero_based = i > 0 ? i - 1 : num_vertices + i;
  if (zero_based < 0 || zero_based >= num_vertices)
    in.fail("vertex index " + std::to_string(i) + " out of range, " + std::to_string(num_vertices) +
            " vertices defined so far");
  return static_cast<int>(zero_based);
}

ObjContent parse_obj(const std::filesystem::path& path, const char* fn) {
  const std::string text = detail::read_file(path, fn);
  detail::require_text(text, fn, path);
  detail::TextCursor in(text, fn, path);
  ObjContent obj;
  // A vertex line takes at least "v 0 0 0\n": reserve no more than that allows.
  obj.mesh.reserve(text.size() / 16, text.size() / 32);
  std::vector<int> corners;
  while (!in.at_end()) {
    const std::string_view keyword = in.token_on_line();
    if (keyword == "v") {
      const double x = in.number_on_line("vertex x coordinate");
      const double y = in.number_on_line("vertex y coordinate");
      const double z = in.number_on_line("vertex z coordinate");
      obj.mesh.add_vertex(x, y, z);
    } else if (keyword == "f" || keyword == "l") {
      corners.clear();
      for (std::string_view t = in.token_on_line(); !t.empty(); t = in.token_on_line())
        corners.push_back(corner_index(in, t, obj.mesh.num_vertices()));
      if (keyword == "f") {
        if (corners.size() < 3)
          in.fail("face with " + std::to_string(corners.size()) + " corners, expected at least 3");
        obj.mesh.add_polygon(corners);
      } else {
        if (corners.size() < 2)
          in.fail("polyline with " + std::to_string(corners.size()) + " points, expected at least 2");
        obj.lines.push_back(corners);
      }
    } else if (std::find(kSkipped.begin(), kSkipped.end(), keyword) == kSkipped.end()) {
      in.fail("unknown statement " + detail::quote(keyword) + ", expected v, f, l or another OBJ keyword");
    }
    in.skip_line();
  }
  return obj;
}

}  // namespace

TriMesh read_obj(const std::filesystem::path& path, Warnings* warnings) {
  constexpr const char* fn = "geometry::read_obj()";
  ObjContent obj = parse_obj(path, fn);
  if (obj.mesh.num_vertices() == 0) detail::io_fail(fn, path, "", "no vertices, expected 'v' statements");
  return obj.mesh.finish(fn, path, warnings);
}

Polylines read_obj_polylines(const std::filesystem::path& path) {
  constexpr const char* fn = "geometry::read_obj_polylines()";
  ObjContent obj = parse_obj(path, fn);
  if (obj.lines.empty()) detail::io_fail(fn, path, "", "no polylines, expected 'l' statements");
  const TriMesh points = obj.mesh.finish(fn, path, nullptr);
  Polylines out;
  out.points.reserve(points.V.rows());
  for (int v = 0; v < points.num_vertices(); ++v) out.points.emplace_back(points.V.row(v).transpose());
  out.lines = std::move(obj.lines);
  return out;
}

namespace {
void append_vertex_line(std::string& s, const Eigen::Vector3d& p) {
  s += "v";
  for (int k = 0; k < 3; ++k) s += ' ', detail::append_number(s, p[k]);
  s += '\n';
}
}  // namespace

void write_obj(const std::filesystem::path& path, const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::write_obj()");
  require_finite_vertices(mesh, "geometry::write_obj()");
  core::write_file_atomically(path, [&](std::ostream& out) {
    std::string s;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      append_vertex_line(s, mesh.V.row(v).transpose());
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
      s += "f";
      for (int k = 0; k < 3; ++k) s += ' ', detail::append_number(s, static_cast<long long>(mesh.F(f, k)) + 1);
      s += '\n';
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    out << s;
  });
}

void write_obj_polylines(const std::filesystem::path& path,
                         const std::vector<std::vector<Eigen::Vector3d>>& polylines) {
  for (size_t i = 0; i < polylines.size(); ++i)
    if (polylines[i].size() < 2)
      throw InvalidArgument("geometry::write_obj_polylines(): polyline " + std::to_string(i) + " has " +
                            std::to_string(polylines[i].size()) + " points, expected at least 2");
  for (size_t i = 0; i < polylines.size(); ++i)
    for (size_t k = 0; k < polylines[i].size(); ++k)
      if (!polylines[i][k].allFinite())
        throw InvalidArgument("geometry::write_obj_polylines(): point " + std::to_string(k) + " of polyline " +
                              std::to_string(i) + " is not finite");
  core::write_file_atomically(path, [&](std::ostream& out) {
    std::string s;
    long long next = 1;
    for (const auto& line : polylines) {
      for (const auto& p : line) append_vertex_line(s, p);
      s += "l";
      for (size_t k = 0; k < line.size(); ++k) s += ' ', detail::append_number(s, next + static_cast<long long>(k));
      s += '\n';
      next += static_cast<long long>(line.size());
      out << s;
      s.clear();
    }
  });
}

}  // namespace lapis::geometry
