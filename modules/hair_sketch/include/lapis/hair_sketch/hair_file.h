// Cem Yuksel's binary .hair format, the exchange format of hair research
// (http://www.cemyuksel.com/research/hairmodels/): a 128-byte header ("HAIR", counts, a bit
// field of the arrays present, defaults, 88 bytes of info) followed by the arrays that are
// present, in order: uint16 segments per strand, float xyz points, float thickness, float
// transparency, float rgb colors. Little-endian, as every published model is.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "lapis/hair_sketch/growth.h"

namespace lapis::hair_sketch {

// Bits of the header's array field.
enum HairArrays : std::uint32_t {
  kHairSegments = 1,
  kHairPoints = 2,
  kHairThickness = 4,
  kHairTransparency = 8,
  kHairColors = 16,
};

// Everything a .hair file holds. An empty per-point or per-strand array means "absent: use
// the default"; points are always present when the file is written by Lapis.
struct HairFile {
  std::uint32_t hair_count = 0;
  std::uint32_t point_count = 0;
  std::vector<std::uint16_t> segments;  // hair_count, or empty (all strands default_segments)
  std::vector<float> points;            // 3 * point_count
  std::vector<float> thickness;         // point_count or empty
  std::vector<float> transparency;      // point_count or empty
  std::vector<float> colors;            // 3 * point_count or empty
  std::uint32_t default_segments = 0;
  float default_thickness = 1.0f;
  float default_transparency = 0.0f;
  std::array<float, 3> default_color{1.0f, 1.0f, 1.0f};
  std::string info;  // at most 87 characters are stored (the field is NUL-terminated)

  std::uint32_t arrays() const;  // the header bit field for the arrays present
};

// Writes file atomically. Throws InvalidArgument when the arrays disagree with the counts
// (or a strand has more than 65535 segments), IoError when writing fails.
void write_hair_file(const std::filesystem::path& path, const HairFile& file);

// Reads and validates a .hair file: signature, known array bits, sizes consistent with the
// counts and with the file length (checked before anything is allocated), segment counts
// summing to the point count, finite points. Throws IoError naming the file and the cause.
HairFile read_hair_file(const std::filesystem::path& path);

// Grown strands as a .hair file (segments and points arrays; info names Lapis). Throws
// InvalidArgument for a strand with more than 65535 segments.
HairFile to_hair_file(const Strands& strands);
// The strands of a file (its points, split by its segment counts).
Strands strands_from_hair_file(const HairFile& file);

}  // namespace lapis::hair_sketch
