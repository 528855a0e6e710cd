// OFF and its variants (COFF, NOFF, CNOFF, STOFF...): a header keyword, "#V #F #E", then one
// vertex per line (extra per-vertex values such as colours ignored) and one polygon per
// line "n i1 ... in [colour]". Reference: Geomview's OFF file format documentation.
#include <string>
#include <vector>

#include "io_text.h"
#include "lapis/geometry/io.h"
#include "mesh_builder.h"

namespace lapis::geometry {
namespace {

constexpr const char* kRead = "geometry::read_off()";

// Smallest text a vertex line ("0 0 0\n") and a triangle line ("3 0 0 0\n") can take:
// counts beyond remaining_bytes / these sizes cannot be honest.
constexpr size_t kMinVertexBytes = 6, kMinFaceBytes = 8;

bool is_off_keyword(std::string_view t) {
  // [ST][C][N][4][n]OFF: we accept the 3D forms only.
  if (t.size() < 3 || t.substr(t.size() - 3) != "OFF") return false;
  for (char c : t.substr(0, t.size() - 3))
    if (c != 'S' && c != 'T' && c != 'C' && c != 'N') return false;
  return true;
}

}  // namespace

TriMesh read_off(const std::filesystem::path& path, Warnings* warnings) {
  const std::string text = detail::read_file(path, kRead);
  detail::require_text(text, kRead, path);
  detail::TextCursor in(text, kRead, path);
  const std::string_view keyword = in.token();
  if (keyword.empty()) in.fail("empty file, expected an 'OFF' header");
  if (!is_off_keyword(keyword)) in.fail("expected an 'OFF' header, found " + detail::quote(keyword));
  const long long nv = in.integer("vertex count");
  const long long nf = in.integer("face count");
  // The edge count is unused and some writers leave it out: optional, but an integer if there.
  if (!in.at_line_end()) in.integer("edge count", true);
  if (nv < 0 || nf < 0)
    in.fail("negative vertex or face count (" + std::to_string(nv) + ", " + std::to_string(nf) + ")");
  const size_t room = in.remaining();
  if (static_cast<unsigned long long>(nv) > room / kMinVertexBytes ||
      static_cast<unsigned long long>(nf) > room / kMinFaceBytes ||
      static_cast<unsigned long long>(nv) * kMinVertexBytes + static_cast<unsigned long long>(nf) * kMinFaceBytes >
          room)
    in.fail("header claims " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
            " faces, more than the remaining " + std::to_string(room) + " bytes can hold");

  detail::MeshBuilder mesh;
  mesh.reserve(static_cast<size_t>(nv), static_cast<size_t>(nf));
  in.skip_line();
  for (long long v = 0; v < nv; ++v) {
    if (in.at_end()) in.fail("file ends after " + std::to_string(v) + " of " + std::to_string(nv) + " vertices");
    const double x = in.number_on_line("vertex x coordinate");
    const double y = in.number_on_line("vertex y coordinate");
    const double z = in.number_on_line("vertex z coordinate");
    mesh.add_vertex(x, y, z);
    in.skip_line();  // normals, colours, texture coordinates
  }
  std::vector<int> corners;
  for (long long f = 0; f < nf; ++f) {
    if (in.at_end()) in.fail("file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const long long n = in.integer("face corner count", true);
    if (n < 3) in.fail("face " + std::to_string(f) + " has " + std::to_string(n) + " corners, expected at least 3");
    if (static_cast<unsigned long long>(n) > in.remaining() / 2)
      in.fail("face " + std::to_string(f) + " claims " + std::to_string(n) + " corners, more than the file holds");
    corners.resize(static_cast<size_t>(n));
    for (long long k = 0; k < n; ++k) {
      const long long i = in.integer("vertex index", true);
      if (i < 0 || i >= nv)
        in.fail("face " + std::to_string(f) + " index " + std::to_string(i) + " out of range [0, " +
                std::to_string(nv) + ")");
      corners[static_cast<size_t>(k)] = static_cast<int>(i);
    }
    mesh.add_polygon(corners);
    in.skip_line();  // face colour
  }
  if (!in.at_end())
    in.fail("unexpected data after " + std::to_string(nf) + " faces, counts in the header disagree with the data");
  return mesh.finish(kRead, path, warnings);
}

void write_off(const std::filesystem::path& path, const TriMesh& mesh) {
  require_indices_in_range(mesh, "geometry::write_off()");
  require_finite_vertices(mesh, "geometry::write_off()");
  core::write_file_atomically(path, [&](std::ostream& out) {
    std::string s = "OFF\n" + std::to_string(mesh.num_vertices()) + " " + std::to_string(mesh.num_faces()) + " 0\n";
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      for (int k = 0; k < 3; ++k) {
        if (k) s += ' ';
        detail::append_number(s, mesh.V(v, k));
      }
      s += '\n';
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    for (int f = 0; f < mesh.num_faces(); ++f) {
      s += "3";
      for (int k = 0; k < 3; ++k) s += ' ', detail::append_number(s, static_cast<long long>(mesh.F(f, k)));
      s += '\n';
      if (s.size() > (1 << 16)) out << s, s.clear();
    }
    out << s;
  });
}

}  // namespace lapis::geometry
