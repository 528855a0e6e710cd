// A corpus of malformed files, made here: each must raise lapis::IoError whose message names
// the function, the file, the place and the problem. Then random mutations of valid files:
// every reader either loads or throws IoError, never crashes, hangs or throws anything else.
#include <doctest/doctest.h>

#include <bit>
#include <cstring>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "test_util.h"

using namespace lapis::geometry;

namespace {

struct Case {
  const char* name;  // file name, extension selects the reader
  std::string content;
  const char* expected;  // substring of the message
};

std::string f32(float v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
std::string i32(std::int32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }
std::string u32(std::uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); }

const std::string kPlyFloatHeader =
    "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

std::string ply_triangle_body(float nan_at_x1 = 0, int index = 2) {
  std::string b = f32(0) + f32(0) + f32(0) + f32(nan_at_x1) + f32(0) + f32(0) + f32(0) + f32(1) + f32(0);
  return b + '\3' + i32(0) + i32(1) + i32(index);
}

std::string stl_binary(std::uint32_t claimed, int actual, float value = 0) {
  std::string s(80, ' ');
  s += u32(claimed);
  for (int t = 0; t < actual; ++t) {
    s += f32(0) + f32(0) + f32(1);
    s += f32(value) + f32(0) + f32(0) + f32(1) + f32(0) + f32(0) + f32(0) + f32(1) + f32(0);
    s += std::string(2, '\0');
  }
  return s;
}

std::string garbage(std::uint32_t seed, size_t n, bool with_nul) {
  std::mt19937 rng(seed);
  std::string s(n, ' ');
  for (char& c : s) c = static_cast<char>(1 + rng() % 255);
  if (with_nul) s[n / 2] = '\0';
  return s;
}

const std::string kLongVertices =
    "0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n0.000000 1.000000 0.000000\n";

std::vector<Case> corpus() {
  return {
      // OFF
      {"empty.off", "", "line 1: empty file, expected an 'OFF' header"},
      {"header.off", "PLY\n3 1 0\n", "line 1: expected an 'OFF' header, found 'PLY'"},
      {"no_counts.off", "OFF\n3\n", "expected face count, found end of file"},
      {"negative.off", "OFF\n-3 1 0\n", "negative vertex or face count (-3, 1)"},
      {"huge.off", "OFF\n2000000000 1 0\n0 0 0\n",
       "header claims 2000000000 vertices and 1 faces, more than the remaining"},
      {"huge_faces.off", "OFF\n3 99999999999 0\n" + kLongVertices, "header claims 3 vertices and 99999999999 faces"},
      {"trunc_v.off", "OFF\n4 1 0\n" + kLongVertices, "line 6: file ends after 3 of 4 vertices"},
      {"trunc_f.off", "OFF\n3 2 0\n" + kLongVertices + "3 0 1 2\n", "file ends after 1 of 2 faces"},
      {"nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", "line 4: non-finite vertex x coordinate 'nan'"},
      {"inf.off", "OFF\n3 1 0\n0 0 0\n1 -inf 0\n0 1 0\n3 0 1 2\n", "line 4: non-finite vertex y coordinate '-inf'"},
      {"letters.off", "OFF\n3 1 0\n0 abc 0\n1 0 0\n0 1 0\n3 0 1 2\n",
       "line 3: expected vertex y coordinate, found 'abc'"},
      {"short_vertex.off", "OFF\n3 1 0\n0.000000 0.000000\n" + kLongVertices.substr(27) + "3 0 1 2\n",
       "line 3: expected vertex z coordinate, found end of line"},
      {"bad_index.off", "OFF\n3 1 0\n" + kLongVertices + "3 0 1 7\n", "line 6: face 0 index 7 out of range [0, 3)"},
      {"neg_index.off", "OFF\n3 1 0\n" + kLongVertices + "3 0 -1 2\n", "face 0 index -1 out of range"},
      {"frac_index.off", "OFF\n3 1 0\n" + kLongVertices + "3 0 1 2.5\n", "expected vertex index, found '2.5'"},
      {"two_corners.off", "OFF\n3 1 0\n" + kLongVertices + "2 0 1\n", "face 0 has 2 corners, expected at least 3"},
      {"many_corners.off", "OFF\n3 1 0\n" + kLongVertices + "1000000 0 1 2\n",
       "face 0 claims 1000000 corners, more than the file holds"},
      {"extra.off", "OFF\n3 1 0\n" + kLongVertices + "3 0 1 2\n3 0 1 2\n",
       "unexpected data after 1 faces, counts in the header disagree"},
      {"nul.off", "OFF\n3 1 0\n" + garbage(1, 200, true), "binary data (NUL byte), expected text"},
      {"garbage.off", garbage(2, 300, false), "expected an 'OFF' header"},
      // OBJ
      {"empty.obj", "", "no vertices, expected 'v' statements"},
      {"comments_only.obj", "# nothing\n\n# here\r\n", "no vertices, expected 'v' statements"},
      {"unknown.obj", "v 0 0 0\nxyz 1 2\n", "line 2: unknown statement 'xyz'"},
      {"bad_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
       "line 4: vertex index 9 out of range, 3 vertices defined so far"},
      {"neg_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n", "vertex index -4 out of range"},
      {"zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
       "expected a vertex index (1-based or negative), found '0'"},
      {"slash_garbage.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 a/1\n", "found 'a/1'"},
      {"nan.obj", "v 0 0 0\nv NaN 0 0\n", "line 2: non-finite vertex x coordinate 'NaN'"},
      {"short_v.obj", "v 1 2", "line 1: expected vertex z coordinate, found end of file"},
      {"two_corners.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3: face with 2 corners, expected at least 3"},
      {"one_point_line.obj", "v 0 0 0\nl 1\n", "line 2: polyline with 1 points, expected at least 2"},
      {"nul.obj", "v 0 0 0\n" + garbage(3, 100, true), "binary data (NUL byte), expected text"},
      {"garbage.obj", garbage(4, 300, false), "unknown statement"},
      // PLY
      {"empty.ply", "", "line 1: empty file, expected 'ply' magic"},
      {"magic.ply", "plx\nformat ascii 1.0\nend_header\n", "expected 'ply' magic, found 'plx"},
      {"no_end.ply", "ply\nformat ascii 1.0\nelement vertex 1\n", "no 'end_header' line"},
      {"no_format.ply", "ply\nelement vertex 0\nend_header\n", "no 'format' line in the header"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
       "line 2: unknown format 'binary_middle_endian'"},
      {"version.ply", "ply\nformat ascii 2.0\nend_header\n", "line 2: expected format version 1.0"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
       "line 4: unknown property type 'float128'"},
      {"count_type.ply", "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\nend_header\n",
       "list count type 'float' is not an integer type"},
      {"keyword.ply", "ply\nformat ascii 1.0\nelephant 3\nend_header\n", "line 3: unknown header keyword 'elephant'"},
      {"orphan.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", "property before any element"},
      {"huge.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty "
       "float z\nend_header\n" +
           std::string(64, '\0'),
       "element 'vertex' claims 4000000000 instances, more than the remaining 64 bytes can hold"},
      {"no_xyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
       "element 'vertex' lacks scalar properties x, y and z"},
      {"no_vertex.ply", "ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n0\n",
       "no 'vertex' element in the header"},
      {"no_indices.ply",
       "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face "
       "1\nproperty int a\nend_header\n0\n",
       "element 'face' has no list property 'vertex_indices'"},
      {"nan.ply", kPlyFloatHeader + ply_triangle_body(std::nanf("")), "non-finite coordinate x of vertex 1"},
      {"bad_index.ply", kPlyFloatHeader + ply_triangle_body(0, 3), "face 0 index 3.000000 out of range [0, 3)"},
      {"list_bomb.ply", kPlyFloatHeader + ply_triangle_body().substr(0, 36) + "\xff" + i32(0) + i32(1) + i32(2),
       "list count 255 of face 0 exceeds the remaining 12 bytes"},
      {"face_bomb.ply",
       kPlyFloatHeader.substr(0, kPlyFloatHeader.find("element face 1")) + "element face 1000\n" +
           kPlyFloatHeader.substr(kPlyFloatHeader.find("property list")) + ply_triangle_body(),
       "element 'face' claims 1000 instances, more than the remaining 49 bytes can hold"},
      {"extra.ply", kPlyFloatHeader + ply_triangle_body() + "junk", "unexpected data after the last element"},
      {"trunc_ascii.ply",
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n0.0 "
       "0.0 0.0\n1.0 0.0 0.0\n0.0",
       "file ends early, expected y of vertex 2"},
      {"ascii_letters.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 "
       "abc 0\n",
       ":line 8: expected y of vertex 0, found 'abc'"},  // lines counted from the file's start
      {"neg_count.ply",
       "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float "
       "z\nelement face 1\nproperty list char int vertex_indices\nend_header\n" +
           ply_triangle_body().substr(0, 36) + "\xff" + i32(0) + i32(1) + i32(2),
       "invalid list count -1"},
      {"huge_count.ply",  // a whole ASCII count no integer holds (was a float-to-int overflow)
       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement "
       "face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n" +
           std::string(38, '3') + " 0 1 2\n",
       "list count 3.33333e+37 of face 0 exceeds the remaining"},
      // STL
      {"empty.stl", "", "empty file, expected 'solid' or an 84-byte binary STL header"},
      {"short.stl", "abc", "byte 3: file ends inside the 84-byte binary STL header and is not ASCII STL"},
      {"count.stl", stl_binary(1000, 2),
       "byte 80: binary STL header claims 1000 triangles (50084 bytes), but the file has 184 bytes"},
      {"nan.stl", stl_binary(1, 1, std::numeric_limits<float>::infinity()), "non-finite coordinate in triangle 0"},
      {"trunc.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n",
       "line 6: expected 'vertex' (a facet has 3), found end of input"},
      {"four.stl",
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 1 1 "
       "0\nendloop\nendfacet\nendsolid\n",
       "line 7: expected 'endloop' after 3 vertices, found 'vertex'"},
      {"nan_ascii.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\n",
       "line 4: non-finite vertex z coordinate 'nan'"},
      {"no_end.stl",
       "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n",
       "file ends early, expected 'facet' or 'endsolid'"},
      // dispatch
      {"mesh.xyz", "whatever", "geometry::read_mesh(): "},
  };
}

std::string reader_name(const std::string& file) {
  const std::string ext = file.substr(file.rfind('.') + 1);
  return ext == "xyz" ? "read_mesh" : "read_" + ext;
}

}  // namespace

TEST_CASE("geometry: every malformed file yields an IoError naming file, place and problem") {
  for (const Case& c : corpus()) {
    const std::string name = c.name;
    CAPTURE(name);
    const auto path = test::write_bytes(c.name, c.content);
    std::string message;
    try {
      read_mesh(path);
      FAIL("no error for ", c.name);
    } catch (const lapis::IoError& e) {
      message = e.what();
    }
    CAPTURE(message);
    CHECK(message.find(c.expected) != std::string::npos);
    CHECK(message.rfind("geometry::" + reader_name(c.name) + "(): " + path.string(), 0) == 0);
  }
  CHECK_THROWS_WITH_AS(read_mesh(test::scratch_dir() / "does_not_exist.off"), doctest::Contains("cannot open"),
                       lapis::IoError);
  CHECK_THROWS_WITH_AS(read_mesh(test::scratch_dir()), doctest::Contains("unknown extension"), lapis::IoError);
  CHECK_THROWS_WITH_AS(read_obj_polylines(test::write_bytes("nolines.obj", "v 0 0 0\n")),
                       doctest::Contains("no polylines, expected 'l' statements"), lapis::IoError);
}

TEST_CASE("geometry: readers survive random mutations of valid files") {
  // Valid seeds in every format, including both binary PLY byte orders and binary STL.
  const TriMesh m = make_icosphere(1);
  std::vector<std::filesystem::path> seeds;
  for (const char* name : {"seed.obj", "seed.off", "seed.stl"}) {
    seeds.push_back(test::scratch_dir() / name);
    write_mesh(seeds.back(), m);
  }
  for (PlyFormat f : {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian}) {
    seeds.push_back(test::scratch_dir() / ("seed" + std::to_string(static_cast<int>(f)) + ".ply"));
    write_ply(seeds.back(), m, f);
  }
  std::mt19937 rng(2024);
  int loaded = 0, rejected = 0;
  for (const auto& seed : seeds) {
    std::ifstream in(seed, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (int trial = 0; trial < 300; ++trial) {
      std::string s = original;
      switch (trial % 4) {
        case 0:
          s.resize(rng() % s.size());
          break;  // truncation
        case 1:
          for (int k = 0; k < 4; ++k) s[rng() % s.size()] ^= static_cast<char>(1 << (rng() % 8));
          break;  // bit flips
        case 2:
          s[rng() % s.size()] = "0123456789-.e \n/#\xff\0"[rng() % 18];
          break;  // plausible bytes
        case 3:
          s.insert(rng() % s.size(), std::string(1 + rng() % 8, static_cast<char>(rng() % 256)));
          break;
      }
      const auto path = test::scratch_dir() / ("mutant" + seed.extension().string());
      test::write_bytes(path.filename().string(), s);
      try {
        const TriMesh r = read_mesh(path);
        // Whatever loads is in range and finite: readers never return a broken mesh.
        CHECK(validate(r, {.check_degenerate = false,
                           .check_duplicates = false,
                           .check_manifold = false,
                           .check_orientation = false})
                  .ok());
        ++loaded;
      } catch (const lapis::IoError&) {
        ++rejected;
      }
    }
  }
  CHECK(rejected > 500);
  CHECK(loaded > 50);
}
