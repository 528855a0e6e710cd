#include "lapis/mesh_deform/selection_io.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "lapis/core/atomic_file.h"
#include "lapis/core/checked_number.h"

namespace lapis::mesh_deform {
namespace {

using nlohmann::json;

std::string read_text(const std::filesystem::path& path, const char* what) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot open " + std::string(what) + " file '" + path.string() + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Eigen::Matrix4d matrix4(const json& m, const std::string& where) {
  if (!m.is_array() || m.size() != 4) throw IoError(where + ": expected 4 rows of 4 numbers");
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    if (!m[r].is_array() || m[r].size() != 4) throw IoError(where + ": expected 4 rows of 4 numbers");
    for (int c = 0; c < 4; ++c)
      T(r, c) = json_finite<IoError>(m[r][c], where + ": row " + std::to_string(r) + " column " + std::to_string(c));
  }
  return T;
}

std::vector<int> indices(const json& a, const std::string& where) {
  if (!a.is_array())
    throw IoError(where + ": expected an array of vertex indices, found " + std::string(a.type_name()));
  std::vector<int> out;
  out.reserve(a.size());
  for (size_t k = 0; k < a.size(); ++k) out.push_back(json_index<IoError>(a[k], where + "[" + std::to_string(k) + "]"));
  return out;
}

json rows(const Eigen::Matrix4d& T) {
  json m = json::array();
  for (int r = 0; r < 4; ++r) m.push_back({T(r, 0), T(r, 1), T(r, 2), T(r, 3)});
  return m;
}

}  // namespace

std::vector<int> read_roi(const std::filesystem::path& path) {
  const std::string text = read_text(path, "ROI");
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '[') {
    json j;
    try {
      j = json::parse(text);
    } catch (const json::exception& e) {
      throw IoError(path.string() + ": expected a JSON array of vertex indices (" + e.what() + ")");
    }
    return indices(j, path.string() + ": ROI");
  }
  std::vector<int> out;
  std::istringstream is(text);
  for (std::string token; is >> token;)
    out.push_back(parse_index<IoError>(token, path.string() + ": ROI entry " + std::to_string(out.size())));
  return out;
}

void write_roi(const std::filesystem::path& path, const std::vector<int>& roi) {
  core::write_file_atomically(path, [&](std::ostream& out) {
    for (size_t k = 0; k < roi.size(); ++k) out << roi[k] << ((k + 1) % 16 == 0 || k + 1 == roi.size() ? '\n' : ' ');
  });
}

Drag read_handles(const std::filesystem::path& file) {
  const std::string path = file.string();
  json j;
  try {
    j = json::parse(read_text(file, "handles"));
  } catch (const json::exception& e) {
    throw IoError(path + ": " + e.what());
  }
  Drag d;
  std::vector<std::vector<Eigen::Matrix4d>> region_frames;
  std::vector<std::vector<Eigen::Vector3d>> point_frames;
  size_t frames = 1;
  try {
    for (const json& r : j.value("regions", json::array())) {
      const std::string where = path + ": region handle " + std::to_string(region_frames.size());
      d.selection.region_handles.push_back(indices(r.at("vertices"), where + ": vertices"));
      std::vector<Eigen::Matrix4d> f;
      for (const json& m : r.at("transforms")) f.push_back(matrix4(m, where));
      if (f.empty()) throw IoError(where + ": no transforms");
      frames = std::max(frames, f.size());
      region_frames.push_back(std::move(f));
    }
    for (const json& p : j.value("points", json::array())) {
      const std::string where = path + ": point handle " + std::to_string(point_frames.size());
      d.selection.point_handles.push_back(json_index<IoError>(p.at("vertex"), where + ": vertex"));
      std::vector<Eigen::Vector3d> f;
      for (const json& t : p.at("translations")) {
        const std::string at = where + ": translation " + std::to_string(f.size());
        if (!t.is_array() || t.size() != 3) throw IoError(at + ": expected 3 numbers");
        f.emplace_back(json_finite<IoError>(t[0], at + " x"), json_finite<IoError>(t[1], at + " y"),
                       json_finite<IoError>(t[2], at + " z"));
      }
      if (f.empty()) throw IoError(path + ": point handle without translations");
      frames = std::max(frames, f.size());
      point_frames.push_back(std::move(f));
    }
  } catch (const json::exception& e) {
    throw IoError(path + ": " + e.what());
  }
  auto at = [&](const auto& list, size_t k) {
    if (list.size() != 1 && list.size() != frames)
      throw IoError(path + ": handles have different frame counts (" + std::to_string(list.size()) + " and " +
                    std::to_string(frames) + ")");
    return list[std::min(k, list.size() - 1)];
  };
  for (size_t k = 0; k < frames; ++k) {
    HandleTransforms t;
    for (const auto& f : region_frames) t.regions.push_back(at(f, k));
    for (const auto& f : point_frames) t.points.push_back(at(f, k));
    d.frames.push_back(std::move(t));
  }
  return d;
}

void write_handles(const std::filesystem::path& path, const Selection& selection,
                   const std::vector<HandleTransforms>& frames) {
  constexpr const char* fn = "mesh_deform::write_handles()";
  if (frames.empty()) throw InvalidArgument(std::string(fn) + ": no frames");
  for (size_t k = 0; k < frames.size(); ++k)
    if (frames[k].regions.size() != selection.region_handles.size() ||
        frames[k].points.size() != selection.point_handles.size())
      throw InvalidArgument(
          std::string(fn) + ": frame " + std::to_string(k) + " has " + std::to_string(frames[k].regions.size()) +
          " region and " + std::to_string(frames[k].points.size()) + " point transforms, expected " +
          std::to_string(selection.region_handles.size()) + " and " + std::to_string(selection.point_handles.size()));
  json j = {{"regions", json::array()}, {"points", json::array()}};
  for (size_t h = 0; h < selection.region_handles.size(); ++h) {
    json transforms = json::array();
    for (const auto& f : frames) transforms.push_back(rows(f.regions[h]));
    j["regions"].push_back({{"vertices", selection.region_handles[h]}, {"transforms", std::move(transforms)}});
  }
  for (size_t h = 0; h < selection.point_handles.size(); ++h) {
    json translations = json::array();
    for (const auto& f : frames) translations.push_back({f.points[h].x(), f.points[h].y(), f.points[h].z()});
    j["points"].push_back({{"vertex", selection.point_handles[h]}, {"translations", std::move(translations)}});
  }
  // nlohmann writes doubles in their shortest round-trip form: the CLI reads back the very
  // transforms the app used.
  core::write_file_atomically(path, [&](std::ostream& out) { out << j.dump(1) << "\n"; });
}

}  // namespace lapis::mesh_deform
