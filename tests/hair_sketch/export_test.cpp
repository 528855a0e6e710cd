// Exports: Cem Yuksel's .hair format (round trip, header layout, hostile files), OBJ
// strands, VTK and raw field images.
#include <doctest/doctest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/hair_sketch/export.h"
#include "lapis/hair_sketch/hair_file.h"
#include "sketch_fixture.h"

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;
namespace fs = std::filesystem;

namespace {

fs::path temp_path(const std::string& name) { return hair_test::temp_path("lapis_hair_export_test", name); }

// Three strands of 4, 1 and 3 points.
Strands sample_strands() {
  Strands s;
  for (int n : {4, 1, 3}) {
    for (int i = 0; i < n; ++i) s.points.emplace_back(0.1f * i + s.count(), -0.25f * i, 1.0f / (i + 3));
    s.offsets.push_back(static_cast<int>(s.points.size()));
  }
  return s;
}

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

void write_bytes(const fs::path& p, const std::string& b) {
  std::ofstream(p, std::ios::binary).write(b.data(), static_cast<std::streamsize>(b.size()));
}

template <class T>
T at(const std::string& b, size_t offset) {
  T v;
  std::memcpy(&v, b.data() + offset, sizeof v);
  return v;
}

template <class T>
void put(std::string& b, size_t offset, T v) {
  std::memcpy(b.data() + offset, &v, sizeof v);
}

}  // namespace

TEST_CASE("hair_sketch: .hair write and read round-trips strands exactly") {
  const Strands s = sample_strands();
  const fs::path p = temp_path("round.hair");
  write_hair_file(p, to_hair_file(s));
  const HairFile f = read_hair_file(p);
  CHECK(f.hair_count == 3);
  CHECK(f.point_count == 8);
  CHECK(f.segments == std::vector<std::uint16_t>{3, 0, 2});
  const Strands back = strands_from_hair_file(f);
  CHECK(back.offsets == s.offsets);
  REQUIRE(back.points.size() == s.points.size());
  for (size_t i = 0; i < s.points.size(); ++i) CHECK(back.points[i] == s.points[i]);
  CHECK(f.info.rfind("Lapis", 0) == 0);
}

TEST_CASE("hair_sketch: .hair header follows Yuksel's layout") {
  HairFile f = to_hair_file(sample_strands());
  f.thickness.assign(f.point_count, 0.5f);
  f.colors.assign(3 * f.point_count, 0.25f);
  f.default_color = {0.1f, 0.2f, 0.3f};
  const fs::path p = temp_path("layout.hair");
  write_hair_file(p, f);
  const std::string b = read_bytes(p);
  // header 128 + uint16 segments + xyz points + thickness + colors, nothing else.
  CHECK(b.size() == 128 + 2 * 3 + 12 * 8 + 4 * 8 + 12 * 8);
  CHECK(b.substr(0, 4) == "HAIR");
  CHECK(at<std::uint32_t>(b, 4) == 3);  // hair count
  CHECK(at<std::uint32_t>(b, 8) == 8);  // point count
  CHECK(at<std::uint32_t>(b, 12) == (kHairSegments | kHairPoints | kHairThickness | kHairColors));
  CHECK(at<float>(b, 20) == 1.0f);                             // default thickness
  CHECK(at<float>(b, 28) == 0.1f);                             // default color r
  CHECK(std::string(b.data() + 40).rfind("Lapis", 0) == 0);    // info
  CHECK(at<std::uint16_t>(b, 128) == 3);                       // first strand's segments
  CHECK(at<float>(b, 134) == sample_strands().points[0].x());  // first point follows
  const HairFile g = read_hair_file(p);
  CHECK(g.thickness == f.thickness);
  CHECK(g.colors == f.colors);
  CHECK(g.transparency.empty());
}

TEST_CASE("hair_sketch: .hair without a segments array uses the default segment count") {
  HairFile f;
  f.hair_count = 2;
  f.point_count = 6;
  f.default_segments = 2;
  for (int i = 0; i < 18; ++i) f.points.push_back(static_cast<float>(i));
  const fs::path p = temp_path("default.hair");
  write_hair_file(p, f);
  CHECK(at<std::uint32_t>(read_bytes(p), 12) == kHairPoints);
  const Strands s = strands_from_hair_file(read_hair_file(p));
  CHECK(s.offsets == std::vector<int>{0, 3, 6});
  f.point_count = 5;
  f.points.resize(15);
  CHECK_THROWS_AS(write_hair_file(p, f), lapis::InvalidArgument);
}

TEST_CASE("hair_sketch: truncated and hostile .hair files are rejected with IoError") {
  const fs::path good = temp_path("good.hair"), bad = temp_path("bad.hair");
  write_hair_file(good, to_hair_file(sample_strands()));
  const std::string b = read_bytes(good);
  const auto rejects = [&](const std::string& bytes, const char* what) {
    write_bytes(bad, bytes);
    CHECK_THROWS_WITH_AS(read_hair_file(bad), doctest::Contains(what), lapis::IoError);
  };
  rejects(b.substr(0, b.size() - 1), "truncated");
  rejects(b.substr(0, 100), "truncated header");
  rejects(b + "x", "trailing bytes");
  std::string sig = b;
  sig[0] = 'X';
  rejects(sig, "signature");
  std::string huge = b;  // a header asking for 4G points must not allocate them
  put<std::uint32_t>(huge, 8, 0xffffffffu);
  put<std::uint32_t>(huge, 4, 0xffffffffu);
  rejects(huge, "truncated");
  std::string bits = b;
  put<std::uint32_t>(bits, 12, 3u | 64u);
  rejects(bits, "unknown array bits");
  std::string sum = b;  // segments no longer add up to the point count
  put<std::uint16_t>(sum, 128, 4);
  rejects(sum, "need 9 points");
  std::string nan = b;
  put<float>(nan, 128 + 6 + 12 * 2, std::numeric_limits<float>::quiet_NaN());
  rejects(nan, "point 2 is not finite");
  CHECK_THROWS_AS(read_hair_file(temp_path("missing.hair")), lapis::IoError);
}

TEST_CASE("hair_sketch: strands export as OBJ polylines, skipping single points") {
  const fs::path p = temp_path("strands.obj");
  write_strands_obj(p, sample_strands());
  const auto lines = lapis::geometry::read_obj_polylines(p);
  CHECK(lines.lines.size() == 2);
  CHECK(lines.points.size() == 7);
}

TEST_CASE("hair_sketch: the field exports as a VTK image and as raw float32") {
  Grid g;
  g.dims = {3, 2, 2};
  g.spacing = 0.5;
  g.origin = {1, 2, 3};
  Field f(g.num_nodes(), 3);
  for (int i = 0; i < f.rows(); ++i) f.row(i) << i, -i, 0.5 * i;
  const fs::path vtk = temp_path("field.vtk"), raw = temp_path("field.raw");
  write_field_vtk(vtk, g, f);
  const std::string text = read_bytes(vtk);
  CHECK(text.find("DATASET STRUCTURED_POINTS") != std::string::npos);
  CHECK(text.find("DIMENSIONS 3 2 2") != std::string::npos);
  CHECK(text.find("ORIGIN 1 2 3") != std::string::npos);
  CHECK(text.find("POINT_DATA 12") != std::string::npos);
  CHECK(text.find("\n11 -11 5.5\n") != std::string::npos);
  write_field_raw(raw, g, f);
  const std::string b = read_bytes(raw);
  REQUIRE(b.size() == 12 * 12);
  CHECK(at<float>(b, 12 * 7 + 4) == -7.0f);
  CHECK_THROWS_WITH_AS(write_field_raw(raw, g, Field(5, 3)), doctest::Contains("write_field_raw()"),
                       lapis::InvalidArgument);
}

TEST_CASE("hair_sketch: an export keeps the strands that grew: no lone roots, no strands of zero length") {
  Strands s = sample_strands();                                         // 4, 1 and 3 points
  for (int i = 0; i < 3; ++i) s.points.emplace_back(7.0f, 7.0f, 7.0f);  // 3 points in one place
  s.offsets.push_back(static_cast<int>(s.points.size()));
  const Strands g = grown_strands(s);
  REQUIRE(g.count() == 2);
  CHECK(g.offsets == std::vector<int>{0, 4, 7});
  for (int i = 0; i < 4; ++i) CHECK(g.points[i] == s.points[i]);
  for (int i = 0; i < 3; ++i) CHECK(g.points[4 + i] == s.points[5 + i]);
  CHECK(grown_strands(g).points == g.points);  // nothing more to drop
}
