// Every number the CLI reads is checked where it is read, every mesh it deforms or merges
// passes the checks of `lapis mesh`, and nothing non-finite is written.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_runner.h"

namespace fs = std::filesystem;

using lapis::cli_test::lapis_cli;
using lapis::cli_test::Result;

namespace {

fs::path scratch() { return lapis::cli_test::scratch_dir("cli_checked"); }

fs::path write_grid(const fs::path& d, const std::string& name, const std::string& extra = "") {
  return lapis::cli_test::write_grid_obj(d / name, extra);
}

std::string write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

Result deform(const fs::path& mesh, const std::string& roi, const std::string& handles, const fs::path& out,
              const std::string& extra = "") {
  return lapis_cli("deform --mesh " + mesh.string() + " --roi " + roi + " --handles " + handles +
                   " --method naive --out " + out.string() + extra);
}

const char* kLift =
    R"({"regions": [{"vertices": [2, 5, 8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0.5],[0,0,0,1]]]}]})";

}  // namespace

TEST_CASE("cli: lapis deform refuses the meshes that lapis mesh calls invalid") {
  const fs::path d = scratch();
  const std::string roi = write(d / "roi.txt", "1 2 4 5 7 8\n"), handles = write(d / "h.json", kLift);
  const fs::path good = write_grid(d, "good.obj");
  REQUIRE(deform(good, roi, handles, d / "out.obj").status == 0);
  const fs::path duplicate = write_grid(d, "duplicate.obj", "f 1 2 5\n");  // the first face again
  const fs::path flat = write_grid(d, "flat.obj", "v 3 0 0\nf 1 2 10\n");  // zero area
  for (const fs::path& mesh : {duplicate, flat}) {
    CAPTURE(mesh.filename().string());
    const Result inspected = lapis_cli("mesh --in " + mesh.string());
    CHECK(inspected.status == 1);
    fs::remove(d / "bad.obj");
    const Result r = deform(mesh, roi, handles, d / "bad.obj");
    CHECK(r.status == 1);
    CHECK(r.output.find("lapis deform: error: " + mesh.string() + ": invalid mesh: ") == 0);
    CHECK_FALSE(fs::exists(d / "bad.obj"));
  }
  const Result merged = lapis_cli("merge --source " + duplicate.string() + " --target " + good.string() + " --pairs " +
                                  write(d / "p.json", R"({"pairs": [{"keys": [{"source": 0, "target": 0}]}]})") +
                                  " --out " + (d / "m.obj").string());
  CHECK(merged.status == 1);
  CHECK(merged.output.find("lapis merge: error: " + duplicate.string() + ": invalid mesh: 1 duplicate face") == 0);
}

TEST_CASE("cli: lapis deform refuses indices that would wrap and writes nothing non-finite") {
  const fs::path d = scratch();
  const fs::path mesh = write_grid(d, "grid.obj"), out = d / "never.obj";
  const std::string roi = write(d / "roi.txt", "1 2 4 5 7 8\n"), handles = write(d / "h.json", kLift);
  // 4294967296 = 2^32 would have been vertex 0, 4294967301 vertex 5.
  Result r = deform(mesh, write(d / "wrap.txt", "1 2 4294967296 5 7 8\n"), handles, out);
  CHECK(r.status == 1);
  CHECK(r.output.find("ROI entry 2: expected an integer in [0, 2147483647], found 4294967296") != std::string::npos);
  r = deform(mesh, roi, write(d / "wrap.json", R"({"points": [{"vertex": 4294967301, "translations": [[0, 0, 1]]}]})"),
             out);
  CHECK(r.status == 1);
  CHECK(r.output.find("point handle 0: vertex: expected an integer in [0, 2147483647], found 4294967301") !=
        std::string::npos);
  r = deform(mesh, write(d / "frac.json", "[1, 2, 4.5]"), handles, out);
  CHECK(r.status == 1);
  CHECK(r.output.find("ROI[2]: expected an integer in [0, 2147483647], found '4.5'") != std::string::npos);
  r = deform(mesh, roi, handles, out, " --iterations 4294967297");
  CHECK(r.status == 2);
  CHECK(r.output.find("--iterations: expected an integer in [1, 1000000], found 4294967297") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  // Translations of 1e308 are finite, the deformation's metrics (or positions) are not: no OBJ,
  // no report, exit 1.
  const std::string far = write(
      d / "far.json",
      R"({"points": [{"vertex": 2, "translations": [[1e308, -1e308, 1e308]]}, {"vertex": 8, "translations": [[-1e308, 1e308, -1e308]]}]})");
  r = deform(mesh, roi, far, out, " --report " + (d / "far_report.json").string());
  CHECK(r.status == 1);
  CHECK(r.output.find("lapis deform: error: ") == 0);
  CHECK(r.output.find("finite") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  CHECK_FALSE(fs::exists(d / "far_report.json"));
}
