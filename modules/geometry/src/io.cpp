// Extension dispatch of read_mesh / write_mesh.
#include <algorithm>
#include <cctype>
#include <string>

#include "io_text.h"
#include "lapis/geometry/io.h"

namespace lapis::geometry {
namespace {
std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}
}  // namespace

TriMesh read_mesh(const std::filesystem::path& path, Warnings* warnings) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return read_obj(path, warnings);
  if (ext == ".off") return read_off(path, warnings);
  if (ext == ".ply") return read_ply(path, warnings);
  if (ext == ".stl") return read_stl(path, warnings);
  detail::io_fail("geometry::read_mesh()", path, "",
                  "unknown extension '" + ext + "', expected .obj, .off, .ply or .stl");
}

void write_mesh(const std::filesystem::path& path, const TriMesh& mesh) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return write_obj(path, mesh);
  if (ext == ".off") return write_off(path, mesh);
  if (ext == ".ply") return write_ply(path, mesh);
  if (ext == ".stl") return write_stl(path, mesh);
  detail::io_fail("geometry::write_mesh()", path, "",
                  "unknown extension '" + ext + "', expected .obj, .off, .ply or .stl");
}

}  // namespace lapis::geometry
