// Round trips of every writer through its reader, polygon and comment handling, atomic and
// finite-only writes, and the real meshes of assets/external/.
#include <doctest/doctest.h>

#include <bit>
#include <fstream>

#include "lapis/core/atomic_file.h"
#include "lapis/core/error.h"
#include "lapis/core/format.h"
#include "lapis/geometry/io.h"
#include "test_util.h"

using namespace lapis::geometry;
namespace fs = std::filesystem;

namespace {
// A tetrahedron with awkward coordinates: exact round trips need shortest-form printing.
TriMesh awkward_tetrahedron() {
  TriMesh m = test::tetrahedron();
  m.V(0, 0) = 0.1 + 0.2;
  m.V(1, 1) = -1e-300;
  m.V(2, 2) = 12345678.901234567;
  m.V(3, 0) = 1.0 / 3.0;
  return m;
}
}  // namespace

TEST_CASE("geometry: every reader round-trips what its writer wrote") {
  const TriMesh m = awkward_tetrahedron();
  for (const char* name : {"rt.obj", "rt.off", "rt.ply"}) {
    CAPTURE(name);
    const fs::path path = test::scratch_dir() / name;
    write_mesh(path, m);
    const TriMesh r = read_mesh(path);
    CHECK(r.V == m.V);
    CHECK(r.F == m.F);
  }
  for (PlyFormat format : {PlyFormat::Ascii, PlyFormat::BinaryLittleEndian, PlyFormat::BinaryBigEndian}) {
    const fs::path path = test::scratch_dir() / "rt_format.ply";
    write_ply(path, m, format);
    const TriMesh r = read_ply(path);
    CHECK(r.V == m.V);
    CHECK(r.F == m.F);
  }
  // STL is float32 and unindexed: positions round to float, connectivity comes back by welding.
  const fs::path stl = test::scratch_dir() / "rt.stl";
  write_mesh(stl, m);
  const TriMesh r = read_stl(stl);
  CHECK(r.F == m.F);
  CHECK(r.V.isApprox(m.V.cast<float>().cast<double>(), 0.0));
}

TEST_CASE("geometry: OBJ polylines round-trip") {
  const std::vector<std::vector<Eigen::Vector3d>> curves = {{{0, 0, 0}, {1, 0.5, 0}, {2, 0, 1e-7}},
                                                            {{5, 5, 5}, {6, 6, 6}}};
  const fs::path path = test::scratch_dir() / "curves.obj";
  write_obj_polylines(path, curves);
  const Polylines p = read_obj_polylines(path);
  REQUIRE(p.lines.size() == 2);
  CHECK(p.lines[0] == std::vector<int>{0, 1, 2});
  CHECK(p.lines[1] == std::vector<int>{3, 4});
  CHECK(p.points[2] == curves[0][2]);
  CHECK(p.points[4] == curves[1][1]);
}

TEST_CASE("geometry: OBJ corner forms, negative indices, polygons, CRLF and comments") {
  const fs::path path =
      test::write_bytes("forms.obj",
                        "# comment\r\nv 0 0 0\r\nv 1 0 0 # trailing\r\nv 1 1 0\r\nv 0 1 0\r\nvt 0 0\r\nvn 0 0 1\r\n"
                        "g quad\r\nf 1/1/1 2//1 3/1 -1\r\n");
  Warnings warnings;
  const TriMesh m = read_obj(path, &warnings);
  REQUIRE(m.num_faces() == 2);
  CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("fan-triangulated 1 polygons") != std::string::npos);
}

TEST_CASE("geometry: OFF without edge count, counts on the keyword line, COFF colours") {
  const TriMesh a = read_off(test::write_bytes("noedges.off", "OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  CHECK(a.num_faces() == 1);
  const TriMesh b = read_off(test::write_bytes(
      "oneline.off", "COFF 3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2 10 20 30\n"));
  CHECK(b.V(1, 0) == 1.0);
  CHECK(b.F.row(0) == Eigen::RowVector3i(0, 1, 2));
}

TEST_CASE("geometry: PLY with unusual types, extra properties and elements") {
  // float coordinates, a confidence property, uint16-counted lists of uint32, an edge element.
  std::string s =
      "ply\r\nformat binary_big_endian 1.0\r\ncomment hi\r\nelement vertex 3\r\nproperty float x\r\n"
      "property float y\r\nproperty float z\r\nproperty uchar confidence\r\nelement face 1\r\n"
      "property list ushort uint vertex_index\r\nelement edge 1\r\nproperty int a\r\nproperty int b\r\nend_header\r\n";
  auto be32 = [&](std::uint32_t v) {
    for (int i = 3; i >= 0; --i) s += static_cast<char>((v >> (8 * i)) & 0xff);
  };
  auto bef = [&](float f) { be32(std::bit_cast<std::uint32_t>(f)); };
  const float xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 2.5f, 0}};
  for (const auto& p : xyz) {
    for (float c : p) bef(c);
    s += '\x07';
  }
  s += '\0', s += '\3';
  be32(0), be32(1), be32(2);
  be32(0), be32(1);
  Warnings warnings;
  const TriMesh m = read_ply(test::write_bytes("types.ply", s), &warnings);
  REQUIRE(m.num_vertices() == 3);
  CHECK(m.V(2, 1) == 2.5);
  CHECK(m.F.row(0) == Eigen::RowVector3i(0, 1, 2));
  REQUIRE(warnings.size() == 1);
  CHECK(warnings[0].find("ignored element 'edge'") != std::string::npos);
}

TEST_CASE("geometry: ASCII STL merges shared corners") {
  const fs::path path = test::write_bytes("two.stl",
                                          "solid two\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                                          "   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
                                          " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n"
                                          "   vertex 0 1 0\n  endloop\n endfacet\nendsolid two\n");
  const TriMesh m = read_stl(path);
  CHECK(m.num_vertices() == 4);
  CHECK(m.num_faces() == 2);
  CHECK(m.F.row(1) == Eigen::RowVector3i(0, 2, 3));
}

TEST_CASE("geometry: writers are atomic and leave no temporary files") {
  const fs::path dir = test::scratch_dir() / "atomic";
  fs::create_directories(dir);
  const fs::path path = dir / "m.off";
  write_mesh(path, test::tetrahedron());
  // A writer that throws half way leaves the previous file intact and no debris.
  CHECK_THROWS_AS(lapis::core::write_file_atomically(path,
                                                     [](std::ostream& out) {
                                                       out << "garbage";
                                                       throw std::runtime_error("crash");
                                                     }),
                  std::runtime_error);
  CHECK(read_mesh(path).F == test::tetrahedron().F);
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  CHECK_THROWS_WITH_AS(write_mesh(dir / "missing_dir" / "m.off", test::tetrahedron()),
                       doctest::Contains("core::write_file_atomically(): "), lapis::IoError);
  CHECK_THROWS_WITH_AS(write_mesh(dir / "m.xyz", test::tetrahedron()), doctest::Contains("unknown extension '.xyz'"),
                       lapis::IoError);
}

TEST_CASE("geometry: writers refuse non-finite positions and leave the previous file") {
  const fs::path dir = test::scratch_dir() / "finite";
  fs::create_directories(dir);
  TriMesh bad = test::tetrahedron();
  bad.V(2, 1) = -std::numeric_limits<double>::quiet_NaN();
  bad.V(2, 2) = std::numeric_limits<double>::infinity();
  for (const char* name : {"m.obj", "m.off", "m.ply", "m.stl"}) {
    CAPTURE(name);
    const fs::path path = dir / name;
    write_mesh(path, test::tetrahedron());
    const std::string ext = path.extension().string().substr(1);
    CHECK_THROWS_WITH_AS(write_mesh(path, bad),
                         ("geometry::write_" + ext + "(): vertex 2 = (" + lapis::format_number(bad.V(2, 0)) +
                          ", -nan, inf) is not finite")
                             .c_str(),
                         lapis::InvalidArgument);
    CHECK(read_mesh(path).num_faces() == 4);  // the previous file
    CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
    fs::remove(path);
  }
  CHECK_THROWS_WITH_AS(
      write_obj_polylines(dir / "l.obj", {{Eigen::Vector3d::Zero(), Eigen::Vector3d(1, std::nan(""), 0)}}),
      "geometry::write_obj_polylines(): point 1 of polyline 0 is not finite", lapis::InvalidArgument);
  CHECK_FALSE(fs::exists(dir / "l.obj"));
}

TEST_CASE("geometry: the real meshes in assets/external load and validate") {
  const char* names[] = {"armadillo",
                         "bunny00",
                         "cactus",
                         "dino",
                         "lion",
                         "camel",
                         "elephant",
                         "refined_elephant",
                         "mannequin-devil",
                         "man",
                         "diplodocus",
                         "ChineseDragon-10kv",
                         "double-torus-example",
                         "double-torus-3-holes"};
  for (const char* name : names) {
    CAPTURE(name);
    const fs::path path = test::external_asset(std::string(name) + ".off");
    if (!fs::exists(path)) {
      FAIL("missing ", path.string(), ": run scripts/setup");
      continue;
    }
    Warnings warnings;
    const TriMesh m = read_mesh(path, &warnings);
    CHECK(m.num_faces() > 100);
    const ValidationReport report = validate(m);
    CHECK_MESSAGE(report.ok(), report.summary());
  }
}
