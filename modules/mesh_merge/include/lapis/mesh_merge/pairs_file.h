// The files that name a merge's inputs beside the two meshes: the pairs file (key
// correspondences per source boundary loop) and the handles file (dependent mode). `lapis
// merge` reads them and the merge app writes them, so both sides share one format:
//   {"pairs": [{"keys": [{"source": 12, "target": 830}, {"source": 40, "target": 17}]}]}
//   {"handles": [5, 6, 7]}
//   {"features": [[40, 41, 42, 57], [300, 301, 302, 318]]}   (§3.5, independent mode)
#pragma once

#include <filesystem>
#include <vector>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

// Throws IoError "mesh_merge::read_pairs_file(): <path>: ..." for a missing file or invalid
// JSON and InvalidArgument (same prefix, naming the JSON element) for a wrong structure or a
// non-integer index. Indices are not range-checked here: check_merge_input() does that
// against the meshes.
std::vector<LoopPair> read_pairs_file(const std::filesystem::path& path);
// Atomic write; throws IoError.
void write_pairs_file(const std::filesystem::path& path, const std::vector<LoopPair>& pairs);

// Same conventions, "mesh_merge::read_handles_file()".
std::vector<int> read_handles_file(const std::filesystem::path& path);
void write_handles_file(const std::filesystem::path& path, const std::vector<int>& handles);

// Same conventions, "mesh_merge::read_features_file()": one vertex list per feature.
std::vector<std::vector<int>> read_features_file(const std::filesystem::path& path);
void write_features_file(const std::filesystem::path& path, const std::vector<std::vector<int>>& features);

}  // namespace lapis::mesh_merge
