#include "lapis/mesh_merge/pairs_file.h"

#include <string>

#include "json_file.h"
#include "lapis/core/checked_number.h"

namespace lapis::mesh_merge {

namespace {

int vertex_index(const nlohmann::json& j, const std::string& fn, const std::string& where) {
  return json_index(j, fn + ": " + where);
}

}  // namespace

std::vector<LoopPair> read_pairs_file(const std::filesystem::path& path) {
  const std::string fn = "mesh_merge::read_pairs_file()";
  const nlohmann::json j = detail::read_json_file(path, fn);
  if (!j.is_object() || !j.contains("pairs") || !j["pairs"].is_array())
    throw InvalidArgument(fn + ": " + path.string() + ": expected {\"pairs\": [{\"keys\": [...]}, ...]}");
  std::vector<LoopPair> pairs;
  for (size_t p = 0; p < j["pairs"].size(); ++p) {
    const auto& jp = j["pairs"][p];
    const std::string where = path.string() + ": pairs[" + std::to_string(p) + "]";
    if (!jp.is_object() || !jp.contains("keys") || !jp["keys"].is_array())
      throw InvalidArgument(fn + ": " + where + " needs a \"keys\" array");
    LoopPair pair;
    for (size_t k = 0; k < jp["keys"].size(); ++k) {
      const auto& jk = jp["keys"][k];
      const std::string kw = where + ".keys[" + std::to_string(k) + "]";
      if (!jk.is_object() || !jk.contains("source") || !jk.contains("target"))
        throw InvalidArgument(fn + ": " + kw + " needs \"source\" and \"target\"");
      pair.keys.push_back(
          {vertex_index(jk["source"], fn, kw + ".source"), vertex_index(jk["target"], fn, kw + ".target")});
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

void write_pairs_file(const std::filesystem::path& path, const std::vector<LoopPair>& pairs) {
  nlohmann::json list = nlohmann::json::array();
  for (const LoopPair& p : pairs) {
    nlohmann::json keys = nlohmann::json::array();
    for (const KeyCorrespondence& k : p.keys) keys.push_back({{"source", k.source}, {"target", k.target}});
    list.push_back({{"keys", std::move(keys)}});
  }
  detail::write_json_file(path, {{"pairs", std::move(list)}});
}

std::vector<int> read_handles_file(const std::filesystem::path& path) {
  const std::string fn = "mesh_merge::read_handles_file()";
  const nlohmann::json j = detail::read_json_file(path, fn);
  if (!j.is_object() || !j.contains("handles") || !j["handles"].is_array())
    throw InvalidArgument(fn + ": " + path.string() + ": expected {\"handles\": [vertex, ...]}");
  std::vector<int> h;
  for (size_t k = 0; k < j["handles"].size(); ++k)
    h.push_back(vertex_index(j["handles"][k], fn, path.string() + ": handles[" + std::to_string(k) + "]"));
  return h;
}

void write_handles_file(const std::filesystem::path& path, const std::vector<int>& handles) {
  detail::write_json_file(path, {{"handles", handles}});
}

std::vector<std::vector<int>> read_features_file(const std::filesystem::path& path) {
  const std::string fn = "mesh_merge::read_features_file()";
  const nlohmann::json j = detail::read_json_file(path, fn);
  if (!j.is_object() || !j.contains("features") || !j["features"].is_array())
    throw InvalidArgument(fn + ": " + path.string() + ": expected {\"features\": [[vertex, ...], ...]}");
  std::vector<std::vector<int>> features;
  for (size_t f = 0; f < j["features"].size(); ++f) {
    const auto& list = j["features"][f];
    const std::string where = path.string() + ": features[" + std::to_string(f) + "]";
    if (!list.is_array()) throw InvalidArgument(fn + ": " + where + " must be an array of vertex indices");
    features.emplace_back();
    for (size_t k = 0; k < list.size(); ++k)
      features.back().push_back(vertex_index(list[k], fn, where + "[" + std::to_string(k) + "]"));
  }
  return features;
}

void write_features_file(const std::filesystem::path& path, const std::vector<std::vector<int>>& features) {
  detail::write_json_file(path, {{"features", features}});
}

}  // namespace lapis::mesh_merge
