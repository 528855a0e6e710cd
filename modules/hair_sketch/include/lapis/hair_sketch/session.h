// Hairstyle sessions as JSON: the document (settings, camera, primitives) and the
// recorded strokes, so a session can be reopened for editing or replayed from its input.
// Numbers are written shortest-round-trip, so load(save(x)) is bit-identical. Saving is
// atomic (temporary file, fsync, rename): a crash mid-save leaves the old file intact.
//
// Format (version 1):
//   {"format": "lapis-hair-session", "version": 1,
//    "settings": {"head_mesh", "scalp_mask", "grid_unknowns", "field_method", "omega",
//                 "roots", "seed", "step", "max_length", "scalp_avoidance", "support",
//                 "tail_segments", optionally "gravity_prior" (the prior's strength),
//                 "field_detail_amplitude" and "field_detail_wavelength"},
//    "camera": {"view": [16, row-major], "projection": [16], "viewport": [x, y, w, h]},
//    "primitives": [{"type": "stream_curve", "viewpoint": [3], "support": "strip",
//                    "points": [[x,y,z],...], "tail_segments"} |
//                   {"type": "dividing_curve", ..., "points", "alpha0", "alpha1", "sigma",
//                    "height", "discontinuity", "samples_per_side"} |
//                   {"type": "ponytail", ..., "spine", "cross_section", "profile_a",
//                    "profile_b", "tightness", "inner_ratio", "outer_ratio"}],
//    "details": [{"type": "curl|wave", "seed", "region": [vertex indices], "frequency", "radius",
//                 "frequency_growth", "radius_growth", "phase_jitter", "radius_jitter",
//                 "root_fade"} |
//                {"type": "clump", ..., "clumps", "strength", "profile"} |
//                {"type": "frizz", ..., "amplitude", "wavelength", "root_fade"} |
//                {"type": "length", ..., "variation"} |
//                {"type": "cut", ..., "camera": {...}, "line": [[x,y],...]}],
//    "strokes": [{"action": "stream_curve|dividing_curve|hint|tilt|ponytail",
//                 "target": i, "camera": {...}, "strokes": [[[x,y],...], ...],
//                 "mirrored": bool, "cameras": [{...} x 4]}]}
// Every key is required except "details" and "strokes" (empty), "target" (-1) and a primitive's
// or a stroke's "mirrored" (false) and "cameras" (a ponytail's four, when the view turned
// between its strokes). The
// parameters are those of strand_detail.h's structs.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "lapis/hair_sketch/document.h"
#include "lapis/hair_sketch/head.h"

namespace lapis::hair_sketch {

struct SessionLimits {
  std::uintmax_t max_file_bytes = 64u << 20;  // larger files are refused before parsing
  std::size_t max_points = 100000;            // per curve or stroke
  std::size_t max_items = 10000;              // primitives, details, strokes
};

std::string session_to_json(const Hairstyle& style);

// Throws IoError "hair_sketch::session_from_json(): <source>: <json path>: <what was
// expected>" for malformed JSON, missing keys, wrong types, non-finite numbers or arrays
// beyond the limits.
Hairstyle session_from_json(std::string_view text, const std::string& source = "<string>",
                            const SessionLimits& limits = {});

// Atomic; absolute head_mesh and scalp_mask paths are written relative to the session's
// directory (which is what load_session_head() resolves them against). Throws IoError when
// writing fails.
void save_session(const std::filesystem::path& path, const Hairstyle& style);
// Throws IoError for an unreadable, oversized or malformed file.
Hairstyle load_session(const std::filesystem::path& path, const SessionLimits& limits = {});

// The session's head: settings.head_mesh / scalp_mask resolved against the session file's
// directory (or mesh_override when given). Throws IoError / InvalidArgument from load_head.
Head load_session_head(const Hairstyle& style, const std::filesystem::path& session_path,
                       const std::filesystem::path& mesh_override = {});

}  // namespace lapis::hair_sketch
