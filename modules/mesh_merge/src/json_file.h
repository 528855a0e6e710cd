// Reading and writing the small JSON files that name a merge's inputs (pairs, handles, regions).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace lapis::mesh_merge::detail {

// Throws IoError "<fn>: <path>: ..." for a missing file or invalid JSON.
nlohmann::json read_json_file(const std::filesystem::path& path, const std::string& fn);
// Atomic write; throws IoError.
void write_json_file(const std::filesystem::path& path, const nlohmann::json& j);

}  // namespace lapis::mesh_merge::detail
