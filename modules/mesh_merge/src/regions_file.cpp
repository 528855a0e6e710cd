#include "lapis/mesh_merge/regions_file.h"

#include <string>

#include "json_file.h"
#include "lapis/core/checked_number.h"

namespace lapis::mesh_merge {
namespace {

constexpr const char* kRead = "mesh_merge::read_regions_file()";

std::vector<int> faces_of_region(const nlohmann::json& j, const std::string& where, const TriMesh& mesh) {
  auto fail = [&](const std::string& what) { throw InvalidArgument(std::string(kRead) + ": " + where + " " + what); };
  if (!j.is_object() || j.contains("faces") == j.contains("vertices"))
    fail("needs one of \"faces\" and \"vertices\" (an array of 0-based indices)");
  const bool by_faces = j.contains("faces");
  const nlohmann::json& list = by_faces ? j["faces"] : j["vertices"];
  if (!list.is_array()) fail(std::string(by_faces ? ".faces" : ".vertices") + " must be an array");
  std::vector<int> indices;
  for (size_t i = 0; i < list.size(); ++i)
    indices.push_back(json_index(
        list[i], std::string(kRead) + ": " + where + (by_faces ? ".faces[" : ".vertices[") + std::to_string(i) + "]",
        by_faces ? kAnyIndex : mesh.num_vertices()));
  if (by_faces) return indices;
  std::vector<char> in(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : indices) in[v] = 1;
  std::vector<int> faces;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (in[mesh.F(f, 0)] && in[mesh.F(f, 1)] && in[mesh.F(f, 2)]) faces.push_back(f);
  return faces;
}

}  // namespace

BoundaryRegions read_regions_file(const std::filesystem::path& path, const TriMesh& source, const TriMesh& target) {
  const nlohmann::json j = detail::read_json_file(path, kRead);
  const std::string at = path.string() + ": ";
  if (!j.is_object() || !j.contains("feature"))
    throw InvalidArgument(
        std::string(kRead) + ": " + at +
        "expected {\"rough\": {...}, \"feature\": {...}, \"target\": {...}} with at least \"feature\"");
  for (const auto& [key, value] : j.items())
    if (key != "rough" && key != "feature" && key != "target")
      throw InvalidArgument(std::string(kRead) + ": " + at + "unknown region \"" + key +
                            "\" (expected rough, feature, target)");
  BoundaryRegions r;
  if (j.contains("rough")) r.roi_faces = faces_of_region(j["rough"], at + "rough", source);
  r.feature_faces = faces_of_region(j["feature"], at + "feature", source);
  if (j.contains("target")) r.target_faces = faces_of_region(j["target"], at + "target", target);
  return r;
}

void write_regions_file(const std::filesystem::path& path, const BoundaryRegions& regions) {
  nlohmann::json j = {{"feature", {{"faces", regions.feature_faces}}}};
  if (!regions.roi_faces.empty()) j["rough"] = {{"faces", regions.roi_faces}};
  if (!regions.target_faces.empty()) j["target"] = {{"faces", regions.target_faces}};
  detail::write_json_file(path, j);
}

}  // namespace lapis::mesh_merge
