#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

namespace {

struct Result {
  int status;
  std::string output;  // stdout and stderr
};

Result lapis_cli(const std::string& args) {
  const std::string cmd = std::string(LAPIS_CLI_EXE) + " " + args + " 2>&1";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(cmd.c_str(), "r"), pclose);
  REQUIRE(pipe);
  std::string out;
  std::array<char, 4096> buf{};
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe.get())) out.append(buf.data(), n);
  const int status = pclose(pipe.release());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

fs::path scratch() {
  const fs::path d = fs::temp_directory_path() / ("lapis_cli_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST_CASE("cli: lapis lists its commands and each has --help") {
  const Result none = lapis_cli("");
  CHECK(none.status == 2);
  CHECK(none.output.find("mesh") != std::string::npos);
  const Result help = lapis_cli("mesh --help");
  CHECK(help.status == 0);
  CHECK(help.output.find("usage: lapis mesh") == 0);
  const Result unknown = lapis_cli("frobnicate");
  CHECK(unknown.status == 2);
  CHECK(unknown.output.find("lapis: unknown command 'frobnicate'") == 0);
}

TEST_CASE("cli: lapis mesh reports topology and converts") {
  const fs::path d = scratch();
  {
    std::ofstream obj(d / "quad.obj");
    obj << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
  }
  const Result r = lapis_cli("mesh --in " + (d / "quad.obj").string() + " --out " + (d / "quad.ply").string() +
                             " --report " + (d / "report.json").string());
  REQUIRE(r.status == 0);
  std::ifstream report(d / "report.json");
  const auto j = nlohmann::json::parse(report);
  CHECK(j["vertices"] == 4);
  CHECK(j["faces"] == 2);
  CHECK(j["boundary_loops"] == 1);
  CHECK(j["euler_characteristic"] == 1);
  CHECK(fs::file_size(d / "quad.ply") > 0);
}

TEST_CASE("cli: failures exit non-zero with one line naming the cause") {
  const fs::path d = scratch();
  const Result missing = lapis_cli("mesh --in " + (d / "nope.off").string());
  CHECK(missing.status == 1);
  CHECK(missing.output.find("lapis mesh: error: geometry::read_off(): ") == 0);
  CHECK(std::count(missing.output.begin(), missing.output.end(), '\n') == 1);
  {
    std::ofstream bad(d / "bad.obj");
    bad << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n";  // a degenerate face
  }
  const Result invalid = lapis_cli("mesh --in " + (d / "bad.obj").string());
  CHECK(invalid.status == 1);
  CHECK(invalid.output.find("invalid mesh") != std::string::npos);
  const Result usage = lapis_cli("mesh --in");
  CHECK(usage.status == 2);
  CHECK(usage.output.find("lapis mesh: --in needs a value") == 0);
}

TEST_CASE("cli: lapis deform drags a handle and reports timings and distortion") {
  const fs::path d = scratch();
  {
    // A 3 x 3 vertex grid: the left column outside the ROI, the right column the handle.
    std::ofstream obj(d / "grid.obj");
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) obj << "v " << i << " " << j << " 0\n";
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int a = j * 3 + i + 1;
        obj << "f " << a << " " << a + 1 << " " << a + 4 << "\nf " << a << " " << a + 4 << " " << a + 3 << "\n";
      }
    std::ofstream roi(d / "roi.txt");
    roi << "1 2 4 5 7 8\n";
    std::ofstream handles(d / "handles.json");
    handles << R"({"regions": [{"vertices": [2, 5, 8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0.5],[0,0,0,1]]]}]})";
  }
  for (const std::string method : {"naive", "implicit", "arap"}) {
    CAPTURE(method);
    const Result r = lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() +
                               " --handles " + (d / "handles.json").string() + " --method " + method + " --out " +
                               (d / "out.obj").string() + " --report " + (d / "report.json").string());
    REQUIRE(r.status == 0);
    std::ifstream report(d / "report.json");
    const auto j = nlohmann::json::parse(report);
    CHECK(j["frames"] == 1);
    CHECK(j["distortion"]["edge_length"]["max"].get<double>() > 0);
    CHECK(fs::file_size(d / "out.obj") > 0);
  }
  const Result bad = lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() +
                               " --handles " + (d / "handles.json").string() + " --method magic --out x.obj");
  CHECK(bad.status == 2);
  {
    std::ofstream roi(d / "small_roi.txt");
    roi << "1 4 7\n";
  }
  const Result outside = lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "small_roi.txt").string() +
                                   " --handles " + (d / "handles.json").string() + " --method naive --out x.obj");
  CHECK(outside.status == 1);
  CHECK(outside.output ==
        "lapis deform: error: mesh_deform::Deformer::precompute(): region handle 0 vertex 2 is outside the ROI\n");
}
