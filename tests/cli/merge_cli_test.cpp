// `lapis merge` end to end on the small shipped example (assets/merge: a dome onto a neck).
#include <doctest/doctest.h>

#include "cli_runner.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

namespace {

using Run = lapis::cli_test::Result;

Run lapis_merge(const std::string& args) { return lapis::cli_test::lapis_cli("merge " + args); }

fs::path asset(const std::string& name) { return fs::path(LAPIS_SOURCE_DIR) / "assets" / "merge" / name; }

fs::path scratch_dir() { return lapis::cli_test::scratch_dir("merge_cli_test"); }

}  // namespace

TEST_CASE("cli: lapis merge writes a watertight merge and its report") {
  const fs::path d = scratch_dir();
  const std::string common =
      "--target " + asset("neck.obj").string() + " --pairs " + asset("dome_on_neck.json").string();
  const Run r = lapis_merge("--source " + asset("dome.obj").string() + " " + common + " --out " +
                            (d / "m.obj").string() + " --report " + (d / "m.json").string());
  REQUIRE_MESSAGE(r.status == 0, r.output);
  std::ifstream in(d / "m.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["seam"]["valid"] == true);
  CHECK(j["seam"]["boundary_edges"] == 0);
  CHECK(j["seam"]["max_target_displacement"] == 0.0);
  CHECK(j["timings_ms"]["total"].get<double>() > 0);
  CHECK(fs::file_size(d / "m.obj") > 1000);

  {
    std::ofstream h(d / "handles.json");
    h << "{\"handles\": [12, 27, 67]}\n";
  }
  const Run dep =
      lapis_merge("--source " + asset("dome_placed.obj").string() + " " + common + " --mode dependent --handles " +
                  (d / "handles.json").string() + " --out " + (d / "dep.obj").string());
  CHECK_MESSAGE(dep.status == 0, dep.output);
  CHECK(dep.output.find("\"mode\": \"dependent\"") != std::string::npos);

  // A feature (§3.5): the dome's top, read off the OBJ's vertex lines.
  {
    std::ifstream obj(asset("dome.obj"));
    std::ofstream f(d / "features.json");
    f << "{\"features\": [[";
    int index = 0, written = 0;
    for (std::string line; std::getline(obj, line);) {
      if (line.rfind("v ", 0) != 0) continue;
      double x, y, z;
      if (std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3 && z > 0.8) f << (written++ ? ", " : "") << index;
      ++index;
    }
    f << "]]}\n";
    REQUIRE(written >= 4);
  }
  const Run feat = lapis_merge("--source " + asset("dome.obj").string() + " " + common + " --features " +
                               (d / "features.json").string() + " --out " + (d / "f.obj").string());
  CHECK_MESSAGE(feat.status == 0, feat.output);
  CHECK(feat.output.find("\"features\": 1") != std::string::npos);
  const Run feat_dep =
      lapis_merge("--source " + asset("dome.obj").string() + " " + common + " --mode dependent --features " +
                  (d / "features.json").string() + " --out " + (d / "fd.obj").string());
  CHECK(feat_dep.status == 2);
  CHECK(feat_dep.output.find("--features needs --mode independent") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("cli: lapis merge --mode transition blends a band and reports it") {
  const fs::path d = scratch_dir();
  const std::string common = "--source " + asset("dome.obj").string() + " --target " + asset("neck.obj").string() +
                             " --pairs " + asset("dome_on_neck.json").string() + " --mode transition";
  for (const std::string keep : {"source", "target"}) {
    CAPTURE(keep);
    const Run r = lapis_merge(common + " --keep " + keep + " --out " + (d / "t.obj").string() + " --report " +
                              (d / "t.json").string());
    REQUIRE_MESSAGE(r.status == 0, r.output);
    std::ifstream in(d / "t.json");
    const nlohmann::json j = nlohmann::json::parse(in);
    CHECK(j["mode"] == "transition");
    CHECK(j["seam"]["valid"] == true);
    CHECK(j["seam"]["boundary_edges"] == 0);
    CHECK(j["seam"]["max_target_displacement"] == 0.0);
    CHECK(j["transition"]["keep"] == keep);
    CHECK(j["transition"]["weight"] == 0.1);
    CHECK(j["transition"]["source_width"].get<double>() > 0);
    CHECK(j["transition"]["band_vertices"].get<int>() > 0);
    CHECK(fs::file_size(d / "t.obj") > 1000);
  }
  const Run w = lapis_merge(common + " --source-width 0.05 --target-width 0.05 --out " + (d / "w.obj").string());
  CHECK_MESSAGE(w.status == 0, w.output);
  CHECK(w.output.find("\"source_width\": 0.05") != std::string::npos);
  // On §3.3.2's boundary condition: the placed dome, its apex held.
  {
    std::ofstream h(d / "apex.json");
    h << "{\"handles\": [12, 27, 67]}\n";
  }
  const Run dep = lapis_merge("--source " + asset("dome_placed.obj").string() + " --target " +
                              asset("neck.obj").string() + " --pairs " + asset("dome_on_neck.json").string() +
                              " --mode transition --transition-boundary dependent --handles " +
                              (d / "apex.json").string() + " --out " + (d / "dep.obj").string());
  CHECK_MESSAGE(dep.status == 0, dep.output);
  CHECK(dep.output.find("\"boundary\": \"dependent\"") != std::string::npos);
  const Run stray = lapis_merge("--source " + asset("dome.obj").string() + " --target " + asset("neck.obj").string() +
                                " --pairs " + asset("dome_on_neck.json").string() +
                                " --transition-boundary dependent --out " + (d / "s.obj").string());
  CHECK(stray.status == 2);
  CHECK(stray.output.find("--transition-boundary needs --mode transition") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("cli: lapis merge fails with one line naming the cause") {
  const fs::path d = scratch_dir();
  {
    std::ofstream p(d / "bad.json");
    p << "{\"pairs\": [{\"keys\": [{\"source\": 0, \"target\": 384}]}]}\n";
  }
  const Run bad = lapis_merge("--source " + asset("dome.obj").string() + " --target " + asset("neck.obj").string() +
                              " --pairs " + (d / "bad.json").string() + " --out " + (d / "x.obj").string());
  CHECK(bad.status == 1);
  CHECK(bad.output.find("mesh_merge::check_merge_input(): pair 0 key 0: source vertex 0 is not on a boundary loop") !=
        std::string::npos);
  const Run mode = lapis_merge("--source a --target b --pairs c --out d --mode sideways");
  CHECK(mode.status == 2);
  CHECK(mode.output.find("--mode must be independent, dependent, transition or optimal") != std::string::npos);
  const Run width = lapis_merge("--source " + asset("dome.obj").string() + " --target " + asset("neck.obj").string() +
                                " --pairs " + asset("dome_on_neck.json").string() + " --out " + (d / "x.obj").string() +
                                " --mode transition --source-width 0");
  CHECK(width.status == 1);
  CHECK(width.output.find("transition source_width and target_width must be finite and > 0") != std::string::npos);
  const Run range = lapis_merge("--source a --target b --pairs c --out d --mode dependent --roi-width -1");
  CHECK(range.status == 2);
  CHECK(range.output.find("--roi-width: expected a finite number in [0, 1e+300], found -1\n") !=
        std::string::npos);  // not 300 digits
  const Run stray = lapis_merge("--source a --target b --pairs c --out d --target-width 0.1");
  CHECK(stray.status == 2);
  CHECK(stray.output.find("--target-width needs --mode transition") != std::string::npos);
  fs::remove_all(d);
}

TEST_CASE("cli: lapis merge --mode optimal finds a cheaper boundary, merges along it and reports both") {
  const fs::path d = scratch_dir();
  const std::string common = "--mode optimal --source " + asset("bump.obj").string() + " --target " +
                             asset("plate.obj").string() + " --regions " + asset("bump_regions.json").string();
  const Run r = lapis_merge(common + " --out " + (d / "o.obj").string() + " --report " + (d / "o.json").string());
  REQUIRE_MESSAGE(r.status == 0, r.output);
  std::ifstream in(d / "o.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const nlohmann::json& b = j["boundary"];
  CHECK(b["energy"].get<double>() < 0.01 * b["user_energy"].get<double>());
  CHECK(b["stopped_by"] == "fixed point");
  CHECK(b["iterations"].size() >= 2);
  CHECK(b["iterations"][0]["energy"] == b["user_energy"]);
  // ∂Ω0 runs around the rough region, the optimal loop inside it: the shorter of the two.
  CHECK(b["loop_length"].get<double>() > 0);
  CHECK(b["loop_length"].get<double>() < b["user_loop_length"].get<double>());
  CHECK(b["loop_vertices"].get<int>() >= 3);
  CHECK(j["optimal_merge"]["seam"]["valid"] == true);
  CHECK(j["user_boundary_merge"]["seam"]["valid"] == true);
  CHECK(j["optimal_merge"]["detail"]["max_distance"].get<double>() <
        j["user_boundary_merge"]["detail"]["max_distance"].get<double>());
  CHECK(fs::file_size(d / "o.obj") > 1000);

  const Run capped = lapis_merge(common + " --max-iterations 1 --out " + (d / "c.obj").string() + " --report " +
                                 (d / "c.json").string());
  REQUIRE_MESSAGE(capped.status == 0, capped.output);
  std::ifstream capped_in(d / "c.json");
  const nlohmann::json c = nlohmann::json::parse(capped_in);
  CHECK(c["boundary"]["stopped_by"] == "iteration cap");
  CHECK(c["boundary"]["iterations"].size() == 2);

  // The feature held (default) keeps its shape along either boundary; --feature free lets it
  // bend as §3.4.1 merges, which the user's boundary through the ripples does.
  CHECK(j["feature"] == "held");
  const Run free =
      lapis_merge(common + " --feature free --out " + (d / "f.obj").string() + " --report " + (d / "f.json").string());
  REQUIRE_MESSAGE(free.status == 0, free.output);
  std::ifstream free_in(d / "f.json");
  const nlohmann::json f = nlohmann::json::parse(free_in);
  CHECK(f["feature"] == "free");
  const double held_user = j["user_boundary_merge"]["feature_distortion"].get<double>(),
               free_user = f["user_boundary_merge"]["feature_distortion"].get<double>();
  MESSAGE("feature distortion along the user's boundary: " << held_user << " held, " << free_user << " free");
  CHECK(held_user < 0.2 * free_user);
  CHECK(j["optimal_merge"]["feature_distortion"].get<double>() < 0.2 * free_user);
  const Run wrong = lapis_merge(common + " --feature fixed --out " + (d / "w.obj").string());
  CHECK(wrong.status == 2);
  CHECK(wrong.output.find("--feature must be held or free") != std::string::npos);

  // A given placement that leaves the plate is refused, and nothing is written.
  const Run off = lapis_merge(common + " --placement 1,0,50,0 --out " + (d / "off.obj").string());
  CHECK(off.status == 1);
  CHECK(off.output.find("maps outside the target region") != std::string::npos);
  CHECK(!fs::exists(d / "off.obj"));
  const Run bad = lapis_merge(common + " --placement 1,0,0 --out " + (d / "bad.obj").string());
  CHECK(bad.status == 2);
  CHECK(bad.output.find("--placement must be SCALE,DEGREES,U,V") != std::string::npos);
  {
    std::ofstream regions(d / "r.json");
    regions << "{\"feature\": {\"faces\": [1], \"vertices\": [2]}}\n";
  }
  const Run both =
      lapis_merge("--mode optimal --source " + asset("bump.obj").string() + " --target " + asset("plate.obj").string() +
                  " --regions " + (d / "r.json").string() + " --out " + (d / "b.obj").string());
  CHECK(both.status == 1);
  CHECK(both.output.find("needs one of \"faces\" and \"vertices\"") != std::string::npos);
  fs::remove_all(d);
}
