#include "lapis/core/asset_path.h"

#include <cstdlib>
#include <system_error>

#include "lapis/core/error.h"

namespace lapis {

namespace fs = std::filesystem;

namespace {

// The running executable's directory (Linux: /proc/self/exe), or empty if unknown.
fs::path executable_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe.parent_path();
}

}  // namespace

std::vector<fs::path> asset_search_dirs() {
  std::vector<fs::path> dirs;
  if (const char* env = std::getenv("LAPIS_ASSET_DIR"); env && *env) dirs.emplace_back(env);
  if (const fs::path exe = executable_dir(); !exe.empty())
    dirs.push_back((exe / ".." / "share" / "lapis").lexically_normal());
#ifdef LAPIS_SOURCE_ASSET_DIR
  dirs.emplace_back(LAPIS_SOURCE_ASSET_DIR);
#endif
  return dirs;
}

fs::path asset_path(const fs::path& relative) {
  const std::vector<fs::path> dirs = asset_search_dirs();
  std::string searched;
  for (const fs::path& dir : dirs) {
    std::error_code ec;
    const fs::path candidate = dir / relative;
    if (fs::exists(candidate, ec)) return candidate;
    searched += (searched.empty() ? "" : ", ") + dir.string();
  }
  throw IoError("lapis::asset_path(): " + relative.string() + " not found in " +
                (dirs.empty() ? std::string("any asset directory") : searched) +
                " (set LAPIS_ASSET_DIR to the directory holding Lapis' assets)");
}

}  // namespace lapis
