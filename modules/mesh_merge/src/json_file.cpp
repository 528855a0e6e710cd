#include "json_file.h"

#include <fstream>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"

namespace lapis::mesh_merge::detail {

nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& fn) {
  std::ifstream in(path);
  if (!in) throw IoError(fn + ": " + path.string() + ": cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw IoError(fn + ": " + path.string() + ": not valid JSON (" + e.what() + ")");
  }
}

void write_json_file(const std::filesystem::path& path, const nlohmann::json& j) {
  core::write_file_atomically(path, [&](std::ostream& out) { out << j.dump() << "\n"; });
}

}  // namespace lapis::mesh_merge::detail
