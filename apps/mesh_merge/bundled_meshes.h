// The meshes lapis-merge offers from its menu: every mesh of merge/ and external/ of the assets
// (lapis::asset_path; external/ holds the real meshes scripts/setup extracts), and presets of a source and a target,
// some cut off whole meshes by a plane (mesh_merge::cut_by_plane), ready to pair.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::merge_app {

struct BundledMesh {
  std::string label;  // "merge/dome.obj"
  std::filesystem::path path;
};

// Sorted by label; external/ may be missing (then only merge/). asset_dir holds merge/ and external/.
std::vector<BundledMesh> bundled_meshes(const std::filesystem::path& asset_dir);

struct MeshPair {
  std::shared_ptr<const geometry::TriMesh> source, target;
  std::string source_name, target_name;
  bool place_source = false;  // sizes differ a lot: start with mesh_merge::suggest_placement()
};

const std::vector<std::string>& preset_names();
// Throws lapis::Error (IoError for a missing file, naming it) for an index out of range too.
MeshPair load_preset_meshes(int preset, const std::filesystem::path& asset_dir);

}  // namespace lapis::merge_app
