// The meshes lapis-merge offers from its menu: every mesh of assets/merge/ and assets/external/
// (the real meshes scripts/setup extracts), and presets of a source and a target, some cut off
// whole meshes by a plane (mesh_merge::cut_by_plane), ready to pair.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::merge_app {

struct BundledMesh {
  std::string label;             // "assets/merge/dome.obj"
  std::filesystem::path path;
};

// Sorted by label; assets/external/ may be missing (then only assets/merge/).
std::vector<BundledMesh> bundled_meshes(const std::filesystem::path& source_dir);

struct MeshPair {
  std::shared_ptr<const geometry::TriMesh> source, target;
  std::string source_name, target_name;
  bool place_source = false;  // sizes differ a lot: start with mesh_merge::suggest_placement()
};

const std::vector<std::string>& preset_names();
// Throws lapis::Error (IoError for a missing file, naming it) for an index out of range too.
MeshPair load_preset_meshes(int preset, const std::filesystem::path& source_dir);

}  // namespace lapis::merge_app
