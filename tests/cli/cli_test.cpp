#include <doctest/doctest.h>

#include "cli_runner.h"

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

using lapis::cli_test::lapis_cli;
using lapis::cli_test::Result;

namespace {
fs::path scratch() { return lapis::cli_test::scratch_dir("cli_test"); }

// Vertex lines of an OBJ file: what a report's vertex count must match.
int obj_vertex_count(const fs::path& path) {
  std::ifstream in(path);
  int n = 0;
  for (std::string line; std::getline(in, line);) n += line.rfind("v ", 0) == 0;
  return n;
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

// `lapis hair`: replaying a bundled session writes a .hair file and a report whose counts
// agree with the session's settings and with the file; failures are one line.
namespace {
nlohmann::json read_cli_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}
}  // namespace

TEST_CASE("cli: lapis hair replays a bundled session into .hair, OBJ and a report") {
  const fs::path d = fs::temp_directory_path() / ("lapis_cli_hair_" + std::to_string(::getpid()));
  fs::create_directories(d);
  const fs::path sessions = fs::path(LAPIS_SOURCE_DIR) / "assets" / "sessions";
  const Result replay =
      lapis_cli("hair --session " + (sessions / "parting.json").string() + " --out-hair " + (d / "p.hair").string() +
                " --out-obj " + (d / "p.obj").string() + " --report " + (d / "r.json").string());
  REQUIRE_MESSAGE(replay.status == 0, replay.output);
  const auto report = read_cli_json(d / "r.json"), settings = read_cli_json(sessions / "parting.json")["settings"];
  // Nearly every root grows a strand (a root whose field is zero grows none) of at least one
  // and at most max_length / step segments; scalp avoidance (§4.6) keeps all but a few
  // percent of the segments off the head.
  const double roots = settings["roots"],
               per_strand = settings["max_length"].get<double>() / settings["step"].get<double>();
  const double strand_count = report["strands"], segments = report["segments"];
  // The root count is a target of the sampling per solid angle, not a cap (a few more or
  // fewer roots land on the scalp, as the head tests allow).
  const double sampled = strand_count + report["roots_without_hair"].get<double>();
  CHECK(sampled >= 0.8 * roots);
  CHECK(sampled <= 1.2 * roots);
  CHECK(strand_count >= 0.95 * sampled);
  CHECK(segments >= strand_count);
  CHECK(segments <= strand_count * per_strand);
  CHECK(report["penetrating_segments"].get<double>() <= 0.05 * segments);
  CHECK(report["solves"].size() == 2);  // the style, then scalp avoidance (§4.6)
  // The .hair file: header counts, then uint16 segments and float xyz points.
  std::ifstream hair(d / "p.hair", std::ios::binary);
  char header[128];
  hair.read(header, 128);
  REQUIRE(hair);
  std::uint32_t strands = 0, points = 0;
  std::memcpy(&strands, header + 4, 4);
  std::memcpy(&points, header + 8, 4);
  CHECK(std::string(header, 4) == "HAIR");
  CHECK(strands == report["strands"].get<std::uint32_t>());
  CHECK(points == report["segments"].get<std::uint32_t>() + strands);
  CHECK(fs::file_size(d / "p.hair") == 128 + 2ull * strands + 12ull * points);
  CHECK(fs::file_size(d / "p.obj") > 0);

  // --field-method overrides the style file's solver. parting.json leaves it to auto, which
  // takes the multigrid path at its grid of 25K unknowns (the thesis' update/downdate only to 10K).
  CHECK(settings["field_method"] == "auto");
  const Result thesis =
      lapis_cli("hair --session " + (sessions / "parting.json").string() + " --field-method thesis --out-hair " +
                (d / "m.hair").string() + " --report " + (d / "m.json").string());
  REQUIRE_MESSAGE(thesis.status == 0, thesis.output);
  const auto m = read_cli_json(d / "m.json");
  for (const auto& s : m["solves"]) CHECK(s["method"] == "thesis-updown");
  for (const auto& s : report["solves"]) CHECK(s["method"] == "multigrid");

  // --gravity-prior 0 turns the session's prior off: the thesis' field, other strands.
  const Result thesis_field =
      lapis_cli("hair --session " + (sessions / "parting.json").string() + " --gravity-prior 0 --out-hair " +
                (d / "t.hair").string() + " --report " + (d / "t.json").string());
  REQUIRE_MESSAGE(thesis_field.status == 0, thesis_field.output);
  CHECK(settings["gravity_prior"].get<double>() > 0);
  CHECK(read_cli_json(d / "t.json")["segments"] != report["segments"]);
}

TEST_CASE("cli: lapis hair fails with one line naming the cause") {
  const Result bad = lapis_cli("hair --session /nonexistent/s.json --out-hair /tmp/x.hair");
  CHECK(bad.status == 1);
  CHECK(bad.output.find("lapis hair: error: hair_sketch::load_session(): /nonexistent/s.json: cannot read") == 0);
  CHECK(std::count(bad.output.begin(), bad.output.end(), '\n') == 1);
  const Result missing = lapis_cli("hair --out-hair /tmp/x.hair");
  CHECK(missing.status == 2);
  CHECK(missing.output.find("--session") != std::string::npos);
  const Result method = lapis_cli("hair --session x.json --field-method fastest --out-hair /tmp/x.hair");
  CHECK(method.status == 2);
  CHECK(method.output.find("--field-method must be auto, thesis, refactorize or multigrid, not 'fastest'") !=
        std::string::npos);
  const Result prior = lapis_cli("hair --session x.json --gravity-prior -1 --out-hair /tmp/x.hair");
  CHECK(prior.status == 2);
  CHECK(prior.output.find("--gravity-prior") != std::string::npos);
  const Result help = lapis_cli("hair --help");
  CHECK(help.status == 0);
  CHECK(help.output.find("usage: lapis hair --session FILE.json") == 0);
}

TEST_CASE("cli: lapis deform drags a handle and reports timings and distortion") {
  const fs::path d = scratch();
  {
    // A 3 x 3 vertex grid: the left column outside the ROI, the right column the handle.
    lapis::cli_test::write_grid_obj(d / "grid.obj");
    std::ofstream roi(d / "roi.txt");
    roi << "1 2 4 5 7 8\n";
    std::ofstream handles(d / "handles.json");
    handles << R"({"regions": [{"vertices": [2, 5, 8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0.5],[0,0,0,1]]]}]})";
  }
  for (const std::string method : {"naive", "implicit", "arap", "edge", "isolines"}) {
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
    if (method == "edge") {
      CHECK(j["weights"] == "uniform");  // the paper's default, not the other methods' cotan
      CHECK(j["edge"]["iterations"] == 4);
      CHECK(j["edge"]["domain"] == "edges");
    }
    if (method == "isolines") {
      CHECK(j["isolines"]["solve"] == "reduced");
      CHECK(j["isolines"]["unknowns"] == 4 * 20);  // the fixed region and one handle: one set of 20
    }
  }
  const Result edge_vertex = lapis_cli(
      "deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() + " --handles " +
      (d / "handles.json").string() + " --method edge --domain vertices --transform isotropic --frame principal" +
      " --iterations 7 --out " + (d / "out.obj").string() + " --report " + (d / "report.json").string());
  REQUIRE(edge_vertex.status == 0);
  {
    std::ifstream report(d / "report.json");
    const auto j = nlohmann::json::parse(report);
    CHECK(j["edge"]["domain"] == "vertices");
    CHECK(j["edge"]["transform"] == "isotropic");
    CHECK(j["edge"]["iterations"] == 7);
  }
  const Result isolines_full =
      lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() + " --handles " +
                (d / "handles.json").string() + " --method isolines --isolines 5 --solve full --fit paper --out " +
                (d / "out.obj").string() + " --report " + (d / "report.json").string());
  REQUIRE(isolines_full.status == 0);
  {
    std::ifstream report(d / "report.json");
    const auto j = nlohmann::json::parse(report);
    CHECK(j["isolines"]["solve"] == "full");
    CHECK(j["isolines"]["fit"] == "paper");
    CHECK(j["isolines"]["unknowns"] == 4 * 5);
  }
  const Result bad_solve =
      lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() + " --handles " +
                (d / "handles.json").string() + " --method isolines --solve exact --out x.obj");
  CHECK(bad_solve.status == 2);
  CHECK(bad_solve.output.find("unknown mode 'exact', expected reduced or full") != std::string::npos);
  const Result bad_domain =
      lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() + " --handles " +
                (d / "handles.json").string() + " --method edge --domain faces --out x.obj");
  CHECK(bad_domain.status == 2);
  CHECK(bad_domain.output.find("unknown domain 'faces', expected one of edges, vertices") != std::string::npos);
  const Result bad = lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() +
                               " --handles " + (d / "handles.json").string() + " --method magic --out x.obj");
  CHECK(bad.status == 2);
  CHECK(bad.output.find("--method must be one of naive, implicit, arap, edge, salient, isolines, not 'magic'") !=
        std::string::npos);
  {
    std::ofstream roi(d / "small_roi.txt");
    roi << "1 4 7\n";
  }
  const Result outside =
      lapis_cli("deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "small_roi.txt").string() +
                " --handles " + (d / "handles.json").string() + " --method naive --out x.obj");
  CHECK(outside.status == 1);
  CHECK(outside.output ==
        "lapis deform: error: mesh_deform::Deformer::precompute(): region handle 0 vertex 2 is outside the ROI\n");
}

TEST_CASE("cli: lapis features writes features, a saliency PLY and a report; lapis deform reads them") {
  const fs::path d = scratch();
  const std::string head = std::string(LAPIS_SOURCE_DIR) + "/assets/head.obj";
  const Result r =
      lapis_cli("features --mesh " + head + " --eigenpairs 30 --aggregate 0.1 --out " + (d / "features.json").string() +
                " --ply " + (d / "saliency.ply").string() + " --report " + (d / "features_report.json").string());
  REQUIRE(r.status == 0);
  std::ifstream report(d / "features_report.json");
  const auto j = nlohmann::json::parse(report);
  CHECK(j["eigenpairs"] == 30);
  CHECK(j["vertices"] == obj_vertex_count(head));
  CHECK(j["lambda_2"].get<double>() > 0);
  CHECK(j["t_min"].get<double>() < j["t_max"].get<double>());
  std::ifstream features(d / "features.json");
  const auto f = nlohmann::json::parse(features);
  CHECK(f["features"].size() == j["features"].get<size_t>());
  std::ifstream ply(d / "saliency.ply");
  std::string magic;
  std::getline(ply, magic);
  CHECK(magic == "ply");

  // deform --method salient with a features file, on the 3 x 3 grid.
  lapis::cli_test::write_grid_obj(d / "grid.obj");
  {
    std::ofstream roi(d / "roi.txt");
    roi << "1 2 4 5 7 8\n";
    std::ofstream handles(d / "handles.json");
    handles << R"({"regions": [{"vertices": [2, 5, 8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0.5],[0,0,0,1]]]}]})";
    std::ofstream grid_features(d / "grid_features.json");
    grid_features << R"({"features": [[3, 4, 6, 7]]})";
    std::ofstream bad(d / "bad_features.json");
    bad << R"({"features": [[3, "four"]]})";
  }
  const std::string base = "deform --mesh " + (d / "grid.obj").string() + " --roi " + (d / "roi.txt").string() +
                           " --handles " + (d / "handles.json").string() + " --out " + (d / "out.obj").string();
  const Result s = lapis_cli(base + " --method salient --no-detect --subspace-vertices 40 --iterations 3 --features " +
                             (d / "grid_features.json").string() + " --report " + (d / "report.json").string());
  REQUIRE(s.status == 0);
  std::ifstream deform_report(d / "report.json");
  const auto k = nlohmann::json::parse(deform_report);
  CHECK(k["salient"]["features"] == 1);
  CHECK(k["salient"]["iterations"] == 3);
  CHECK(k["salient"]["strays"] == 0);
  CHECK(k["salient"]["handle_residual"].get<double>() < 0.5);
  const Result cgal = lapis_cli(base + " --method salient --no-detect --subspace cgal --subspace-vertices 20");
  CHECK(cgal.status == 0);
  const Result unknown_subspace = lapis_cli(base + " --method salient --subspace magic");
  CHECK(unknown_subspace.status == 2);
  CHECK(unknown_subspace.output.find("--subspace must be lattice or cgal") != std::string::npos);
  const Result bad = lapis_cli(base + " --method salient --no-detect --features " + (d / "bad_features.json").string());
  CHECK(bad.status == 1);
  CHECK(bad.output.find("bad_features.json: feature 0 entry 1") != std::string::npos);
  const Result misplaced = lapis_cli(base + " --method arap --features " + (d / "grid_features.json").string());
  CHECK(misplaced.status == 2);
  CHECK(misplaced.output.find("--features is an option of --method salient") != std::string::npos);
}

TEST_CASE("cli: lapis transfer carries poses onto a target and names mismatched handles") {
  const fs::path d = scratch();
  lapis::cli_test::write_grid_obj(d / "grid.obj");
  {
    std::ofstream roi(d / "roi.txt");
    roi << "1 2 4 5 7 8\n";
    std::ofstream handles(d / "handles.json");
    handles << R"({"regions": [{"vertices": [2, 5, 8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
    std::ofstream two(d / "two.json");
    two << R"({"regions": [{"vertices": [2], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]},)"
        << R"({"vertices": [8], "transforms": [[[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]]}]})";
  }
  const std::string common = "transfer --source " + (d / "grid.obj").string() + " --source-handles " +
                             (d / "handles.json").string() + " --source-roi " + (d / "roi.txt").string() +
                             " --target " + (d / "grid.obj").string() + " --target-roi " + (d / "roi.txt").string();
  const Result r = lapis_cli(common + " --source-deformed " + (d / "grid.obj").string() + "," +
                             (d / "grid.obj").string() + " --target-handles " + (d / "handles.json").string() +
                             " --out " + (d / "t.obj").string() + " --report " + (d / "t.json").string());
  REQUIRE(r.status == 0);
  CHECK(fs::file_size(d / "t_0.obj") > 0);
  CHECK(fs::file_size(d / "t_1.obj") > 0);
  std::ifstream report(d / "t.json");
  const auto j = nlohmann::json::parse(report);
  CHECK(j["poses"].size() == 2);
  CHECK(j["poses"][0]["eq11_residual"].get<double>() < 1e-12);  // the rest pose: the identity
  CHECK(j["handles"] == 2);
  const Result bad = lapis_cli(common + " --source-deformed " + (d / "grid.obj").string() + " --target-handles " +
                               (d / "two.json").string() + " --out " + (d / "t.obj").string());
  CHECK(bad.status == 1);
  CHECK(bad.output.find("the handles do not correspond: the source has 1 region") != std::string::npos);
}
