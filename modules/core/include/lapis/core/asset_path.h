// Where the runtime assets (the bundled head, sessions, the meshes the apps open by default)
// are found at run time. An install keeps them in <prefix>/share/lapis beside <prefix>/bin;
// executables run from the build tree use the source tree's assets/.
#pragma once

#include <filesystem>
#include <vector>

namespace lapis {

// The directories searched, in order: $LAPIS_ASSET_DIR when set; <directory of the running
// executable>/../share/lapis; the source tree's assets/ as configured (for running from the
// build tree; an installed executable works without it). Directories that do not exist are
// listed too: asset_path's error names them.
std::vector<std::filesystem::path> asset_search_dirs();

// <dir>/<relative> for the first directory of asset_search_dirs() that has it, e.g.
// asset_path("head.obj") or asset_path("merge") (a directory). Throws IoError naming the
// asset and every place searched when none has it.
std::filesystem::path asset_path(const std::filesystem::path& relative);

}  // namespace lapis
