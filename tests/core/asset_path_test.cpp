// The run-time asset lookup: $LAPIS_ASSET_DIR, then share/lapis beside the executable's bin/,
// then the source tree; a missing asset names every place searched.
#include <doctest/doctest.h>

#include <unistd.h>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "lapis/core/asset_path.h"
#include "lapis/core/error.h"

namespace fs = std::filesystem;
using lapis::asset_path;
using lapis::asset_search_dirs;

namespace {

// Sets (or unsets, for nullopt) LAPIS_ASSET_DIR for the scope, restoring it after.
class AssetDirEnv {
 public:
  explicit AssetDirEnv(const std::optional<fs::path>& dir) {
    if (const char* old = std::getenv("LAPIS_ASSET_DIR")) old_ = old;
    if (dir)
      ::setenv("LAPIS_ASSET_DIR", dir->c_str(), 1);
    else
      ::unsetenv("LAPIS_ASSET_DIR");
  }
  ~AssetDirEnv() {
    if (old_)
      ::setenv("LAPIS_ASSET_DIR", old_->c_str(), 1);
    else
      ::unsetenv("LAPIS_ASSET_DIR");
  }

 private:
  std::optional<std::string> old_;
};

fs::path scratch_dir() {
  const fs::path d = fs::temp_directory_path() / ("lapis_asset_path_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

const fs::path kSourceAssets = fs::path(LAPIS_SOURCE_DIR) / "assets";

}  // namespace

TEST_CASE("core: asset_search_dirs lists $LAPIS_ASSET_DIR, share/lapis beside bin/, then the source tree") {
  const fs::path env = scratch_dir() / "env";
  const AssetDirEnv set(env);
  const std::vector<fs::path> dirs = asset_search_dirs();
  REQUIRE(dirs.size() == 3);
  CHECK(dirs[0] == env);
  const fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  CHECK(dirs[1] == (exe_dir / ".." / "share" / "lapis").lexically_normal());
  CHECK(fs::equivalent(dirs[2], kSourceAssets));
}

TEST_CASE("core: asset_path takes an asset from $LAPIS_ASSET_DIR before the source tree") {
  const fs::path env = scratch_dir() / "override";
  fs::create_directories(env);
  std::ofstream(env / "head.obj") << "v 0 0 0\n";
  const AssetDirEnv set(env);
  CHECK(asset_path("head.obj") == env / "head.obj");
  // What the override lacks still comes from further down the list.
  CHECK(fs::equivalent(asset_path("head_scalp.txt"), kSourceAssets / "head_scalp.txt"));
  fs::remove_all(env);
}

TEST_CASE("core: asset_path finds the source tree's files and directories without $LAPIS_ASSET_DIR") {
  const AssetDirEnv unset(std::nullopt);
  CHECK(asset_search_dirs().size() == 2);
  CHECK(fs::equivalent(asset_path("head.obj"), kSourceAssets / "head.obj"));
  CHECK(fs::is_directory(asset_path("sessions")));
}

TEST_CASE("core: a missing asset is an IoError naming it and every place searched") {
  const fs::path env = scratch_dir() / "empty";
  const AssetDirEnv set(env);
  try {
    asset_path("no/such_asset.obj");
    FAIL("asset_path returned for a missing asset");
  } catch (const lapis::IoError& e) {
    const std::string what = e.what();
    CHECK(what.rfind("lapis::asset_path(): no/such_asset.obj not found in ", 0) == 0);
    for (const fs::path& dir : asset_search_dirs()) CHECK_MESSAGE(what.find(dir.string()) != std::string::npos, dir);
    CHECK(what.find("LAPIS_ASSET_DIR") != std::string::npos);
  }
}
