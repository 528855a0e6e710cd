// Cem Yuksel's .hair format: writer, validating reader, conversion from grown strands.
#include "lapis/hair_sketch/hair_file.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"

namespace lapis::hair_sketch {
namespace {

// The format stores native little-endian words; every published model is little-endian.
static_assert(std::endian::native == std::endian::little, "the .hair format is little-endian");

constexpr std::size_t kHeaderBytes = 128;
constexpr std::size_t kInfoBytes = 88;
constexpr std::uint32_t kKnownArrays = kHairSegments | kHairPoints | kHairThickness | kHairTransparency | kHairColors;

struct Header {
  char signature[4];
  std::uint32_t hair_count, point_count, arrays, default_segments;
  float default_thickness, default_transparency, default_color[3];
  char info[kInfoBytes];
};
static_assert(sizeof(Header) == kHeaderBytes, "the .hair header is 128 bytes");

template <class T>
void write_array(std::ostream& out, const std::vector<T>& v) {
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}

void check_sizes(const HairFile& f, const char* fn) {
  const auto fail = [&](const std::string& what) { throw InvalidArgument(std::string(fn) + ": " + what); };
  if (f.points.size() != 3ull * f.point_count)
    fail("points has " + std::to_string(f.points.size()) +
         " floats, expected 3 * point_count = " + std::to_string(3ull * f.point_count));
  if (!f.segments.empty() && f.segments.size() != f.hair_count)
    fail("segments has " + std::to_string(f.segments.size()) +
         " entries, expected hair_count = " + std::to_string(f.hair_count));
  if (!f.thickness.empty() && f.thickness.size() != f.point_count) fail("thickness is not per point");
  if (!f.transparency.empty() && f.transparency.size() != f.point_count) fail("transparency is not per point");
  if (!f.colors.empty() && f.colors.size() != 3ull * f.point_count) fail("colors is not 3 per point");
  std::uint64_t expected = 0;
  if (f.segments.empty())
    expected = std::uint64_t(f.hair_count) * (std::uint64_t(f.default_segments) + 1);
  else
    for (auto s : f.segments) expected += std::uint64_t(s) + 1;
  if (expected != f.point_count)
    fail("strands need " + std::to_string(expected) + " points, point_count is " + std::to_string(f.point_count));
}

}  // namespace

std::uint32_t HairFile::arrays() const {
  std::uint32_t a = 0;
  if (!segments.empty()) a |= kHairSegments;
  if (!points.empty()) a |= kHairPoints;
  if (!thickness.empty()) a |= kHairThickness;
  if (!transparency.empty()) a |= kHairTransparency;
  if (!colors.empty()) a |= kHairColors;
  return a;
}

void write_hair_file(const std::filesystem::path& path, const HairFile& f) {
  check_sizes(f, "hair_sketch::write_hair_file()");
  Header h{};
  std::memcpy(h.signature, "HAIR", 4);
  h.hair_count = f.hair_count;
  h.point_count = f.point_count;
  h.arrays = f.arrays();
  h.default_segments = f.default_segments;
  h.default_thickness = f.default_thickness;
  h.default_transparency = f.default_transparency;
  for (int c = 0; c < 3; ++c) h.default_color[c] = f.default_color[c];
  std::memcpy(h.info, f.info.data(), std::min(f.info.size(), kInfoBytes - 1));
  core::write_file_atomically(path, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    write_array(out, f.segments);
    write_array(out, f.points);
    write_array(out, f.thickness);
    write_array(out, f.transparency);
    write_array(out, f.colors);
  });
}

HairFile read_hair_file(const std::filesystem::path& path) {
  const std::string where = "hair_sketch::read_hair_file(): " + path.string() + ": ";
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(where + "cannot open");
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw IoError(where + "cannot stat: " + ec.message());
  if (size < kHeaderBytes) throw IoError(where + "truncated header: " + std::to_string(size) + " bytes, expected 128");
  Header h{};
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  if (!in) throw IoError(where + "cannot read the header");
  if (std::memcmp(h.signature, "HAIR", 4) != 0) throw IoError(where + "signature is not \"HAIR\"");
  if (h.arrays & ~kKnownArrays)
    throw IoError(where + "unknown array bits 0x" + [&] {
      char buf[16];
      std::snprintf(buf, sizeof buf, "%x", h.arrays & ~kKnownArrays);
      return std::string(buf);
    }());
  // Every size is computed in 64 bits and compared with the file before allocating, so a
  // hostile header cannot request gigabytes.
  const std::uint64_t n = h.point_count, m = h.hair_count;
  std::uint64_t need = kHeaderBytes;
  if (h.arrays & kHairSegments) need += 2 * m;
  if (h.arrays & kHairPoints) need += 12 * n;
  if (h.arrays & kHairThickness) need += 4 * n;
  if (h.arrays & kHairTransparency) need += 4 * n;
  if (h.arrays & kHairColors) need += 12 * n;
  if (need != size)
    throw IoError(where + (need > size ? "truncated: " : "trailing bytes: ") + "the header's counts (" +
                  std::to_string(m) + " strands, " + std::to_string(n) + " points) need " + std::to_string(need) +
                  " bytes, the file has " + std::to_string(size));
  if (!(h.arrays & kHairPoints)) throw IoError(where + "no points array");

  HairFile f;
  f.hair_count = h.hair_count;
  f.point_count = h.point_count;
  f.default_segments = h.default_segments;
  f.default_thickness = h.default_thickness;
  f.default_transparency = h.default_transparency;
  for (int c = 0; c < 3; ++c) f.default_color[c] = h.default_color[c];
  f.info.assign(h.info, strnlen(h.info, kInfoBytes));
  const auto read = [&](auto& v, std::uint64_t count, const char* name) {
    v.resize(count);
    in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(count * sizeof(v[0])));
    if (!in) throw IoError(where + "cannot read the " + name + " array");
  };
  if (h.arrays & kHairSegments) read(f.segments, m, "segments");
  read(f.points, 3 * n, "points");
  if (h.arrays & kHairThickness) read(f.thickness, n, "thickness");
  if (h.arrays & kHairTransparency) read(f.transparency, n, "transparency");
  if (h.arrays & kHairColors) read(f.colors, 3 * n, "colors");
  try {
    check_sizes(f, "");
  } catch (const InvalidArgument& e) {
    throw IoError(where + std::string(e.what()).substr(2));
  }
  for (std::uint64_t i = 0; i < f.points.size(); ++i)
    if (!std::isfinite(f.points[i])) throw IoError(where + "point " + std::to_string(i / 3) + " is not finite");
  return f;
}

HairFile to_hair_file(const Strands& strands) {
  HairFile f;
  f.hair_count = static_cast<std::uint32_t>(strands.count());
  f.point_count = static_cast<std::uint32_t>(strands.points.size());
  f.segments.reserve(strands.count());
  for (int s = 0; s < strands.count(); ++s) {
    const int segs = strands.offsets[s + 1] - strands.offsets[s] - 1;
    if (segs < 0 || segs > 65535)
      throw InvalidArgument("hair_sketch::to_hair_file(): strand " + std::to_string(s) + " has " +
                            std::to_string(segs) + " segments, the format stores 0..65535");
    f.segments.push_back(static_cast<std::uint16_t>(segs));
  }
  f.points.reserve(3 * strands.points.size());
  for (const auto& p : strands.points) f.points.insert(f.points.end(), {p.x(), p.y(), p.z()});
  f.info = "Lapis hair_sketch (vector-field hairstyle, Fu thesis ch. 4)";
  return f;
}

Strands strands_from_hair_file(const HairFile& file) {
  check_sizes(file, "hair_sketch::strands_from_hair_file()");
  Strands s;
  s.points.reserve(file.point_count);
  for (std::uint32_t i = 0; i < file.point_count; ++i)
    s.points.emplace_back(file.points[3 * i], file.points[3 * i + 1], file.points[3 * i + 2]);
  int offset = 0;
  for (std::uint32_t k = 0; k < file.hair_count; ++k) {
    offset += (file.segments.empty() ? int(file.default_segments) : int(file.segments[k])) + 1;
    s.offsets.push_back(offset);
  }
  return s;
}

}  // namespace lapis::hair_sketch
