// The selection files of `lapis deform`, shared by the CLI and the deform app so that what
// the app saves the CLI reads and vice versa:
//   ROI      vertex indices, as a JSON array or whitespace-separated text.
//   handles  {"regions": [{"vertices": [..], "transforms": [M, ...]}],
//             "points": [{"vertex": i, "translations": [[x, y, z], ...]}]}
//            with M a 4x4 matrix as 4 rows applied to rest positions; each entry of
//            "transforms" / "translations" is one frame of a drag (all handles the same
//            count, or 1 = held).
#pragma once

#include <filesystem>
#include <vector>

#include "lapis/mesh_deform/deformer.h"

namespace lapis::mesh_deform {

// A selection with the frames of a drag, as a handles file holds it.
struct Drag {
  Selection selection;                   // roi is filled by the caller (it is a separate file)
  std::vector<HandleTransforms> frames;  // at least one
};

// Throws IoError naming the file when it cannot be read or is malformed. Indices are not
// range-checked here (the deformer does that with its own message).
std::vector<int> read_roi(const std::filesystem::path& path);
// Whitespace-separated text, 16 indices a line. Atomic; throws IoError.
void write_roi(const std::filesystem::path& path, const std::vector<int>& roi);

// Throws IoError naming the file (and the handle) on malformed content or different frame
// counts. The returned selection's roi is empty.
Drag read_handles(const std::filesystem::path& path);
// Writes the handles of `selection` with one transform per frame of `frames` (at least one;
// counts must match the selection, else InvalidArgument). Numbers round-trip exactly. Atomic.
void write_handles(const std::filesystem::path& path, const Selection& selection,
                   const std::vector<HandleTransforms>& frames);

}  // namespace lapis::mesh_deform
