// `lapis deform`: the mesh_deform module headless. Loads a mesh, an ROI and handles, runs a
// drag (one or more frames of handle transforms) with the chosen method, writes the last
// frame and a JSON report (timings, degenerate vertices, distortion metrics).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "args.h"
#include "command.h"
#include "lapis/geometry/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/naive_laplacian.h"

namespace lapis::cli {
namespace {

using nlohmann::json;
using namespace lapis::mesh_deform;

constexpr const char* kUsage =
    "usage: lapis deform --mesh IN --roi ROI --handles HANDLES.json --method naive|implicit|arap\n"
    "                    [--weights cotan|uniform] [--scale-features] [--iterations N]\n"
    "                    --out OUT.obj [--report OUT.json]\n"
    "  ROI: vertex indices, as a JSON array or whitespace-separated text; 'all' for every vertex.\n"
    "  HANDLES.json: {\"regions\": [{\"vertices\": [..], \"transforms\": [M, ...]}],\n"
    "                 \"points\": [{\"vertex\": i, \"translations\": [[x, y, z], ...]}]}\n"
    "  with M a 4x4 matrix as 4 rows of 4 numbers applied to rest positions. Each entry of\n"
    "  \"transforms\"/\"translations\" is one frame of a drag (all handles the same frame count,\n"
    "  or 1 = held); the implicit method follows rotations accumulated over the frames.\n"
    "  --scale-features: implicit Eq. 2.11 instead of 2.10. --iterations: ARAP per frame (10).\n"
    "  Writes the last frame to OUT; the report holds timings, degenerate vertices, metrics.\n";

std::vector<int> read_indices(const std::string& spec, int n, const char* what) {
  std::vector<int> out;
  if (spec == "all") {
    for (int i = 0; i < n; ++i) out.push_back(i);
    return out;
  }
  std::ifstream in(spec);
  if (!in) throw IoError("cannot open " + std::string(what) + " file '" + spec + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  const size_t first = text.find_first_not_of(" \t\r\n");
  if (first != std::string::npos && text[first] == '[') {
    try {
      return json::parse(text).get<std::vector<int>>();
    } catch (const json::exception& e) {
      throw IoError("" + spec + ": expected a JSON array of vertex indices (" + e.what() + ")");
    }
  }
  std::istringstream is(text);
  long v;
  while (is >> v) out.push_back(static_cast<int>(v));
  if (!is.eof()) throw IoError("" + spec + ": expected whitespace-separated vertex indices");
  return out;
}

Eigen::Matrix4d matrix4(const json& m, const std::string& where) {
  if (!m.is_array() || m.size() != 4) throw IoError("" + where + ": expected 4 rows of 4 numbers");
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    if (!m[r].is_array() || m[r].size() != 4) throw IoError("" + where + ": expected 4 rows of 4 numbers");
    for (int c = 0; c < 4; ++c) T(r, c) = m[r][c].get<double>();
  }
  return T;
}

struct Drag {
  Selection selection;
  std::vector<HandleTransforms> frames;
};

Drag read_handles(const std::string& path, std::vector<int> roi) {
  std::ifstream in(path);
  if (!in) throw IoError("cannot open handles file '" + path + "'");
  json j;
  try {
    j = json::parse(in);
  } catch (const json::exception& e) {
    throw IoError("" + path + ": " + e.what());
  }
  Drag d;
  d.selection.roi = std::move(roi);
  std::vector<std::vector<Eigen::Matrix4d>> region_frames;
  std::vector<std::vector<Eigen::Vector3d>> point_frames;
  size_t frames = 1;
  try {
    for (const json& r : j.value("regions", json::array())) {
      d.selection.region_handles.push_back(r.at("vertices").get<std::vector<int>>());
      std::vector<Eigen::Matrix4d> f;
      const std::string where = path + ": region handle " + std::to_string(region_frames.size());
      for (const json& m : r.at("transforms")) f.push_back(matrix4(m, where));
      if (f.empty()) throw IoError("" + where + ": no transforms");
      frames = std::max(frames, f.size());
      region_frames.push_back(std::move(f));
    }
    for (const json& p : j.value("points", json::array())) {
      d.selection.point_handles.push_back(p.at("vertex").get<int>());
      std::vector<Eigen::Vector3d> f;
      for (const json& t : p.at("translations")) f.emplace_back(t.at(0).get<double>(), t.at(1).get<double>(), t.at(2).get<double>());
      if (f.empty()) throw IoError("" + path + ": point handle without translations");
      frames = std::max(frames, f.size());
      point_frames.push_back(std::move(f));
    }
  } catch (const json::exception& e) {
    throw IoError("" + path + ": " + e.what());
  }
  auto at = [&](const auto& list, size_t k) {
    if (list.size() != 1 && list.size() != frames)
      throw IoError("" + path + ": handles have different frame counts (" + std::to_string(list.size()) +
                    " and " + std::to_string(frames) + ")");
    return list[std::min(k, list.size() - 1)];
  };
  for (size_t k = 0; k < frames; ++k) {
    HandleTransforms t;
    for (const auto& f : region_frames) t.regions.push_back(at(f, k));
    for (const auto& f : point_frames) t.points.push_back(at(f, k));
    d.frames.push_back(std::move(t));
  }
  return d;
}

json summary(const Summary& s) { return {{"mean", s.mean}, {"max", s.max}, {"p95", s.p95}}; }

int run(const std::vector<std::string>& argv) {
  const Args args(argv, {"--scale-features"});
  args.allow_only({"--mesh", "--roi", "--handles", "--method", "--weights", "--scale-features", "--iterations", "--out", "--report"});
  const std::string method = args.get("--method");
  const std::string weights = args.get("--weights", "cotan");
  if (method != "naive" && method != "implicit" && method != "arap")
    throw UsageError("--method must be naive, implicit or arap, not '" + method + "'");
  if (weights != "cotan" && weights != "uniform")
    throw UsageError("--weights must be cotan or uniform, not '" + weights + "'");
  const std::string out_path = args.get("--out");
  const geometry::TriMesh mesh = geometry::read_mesh(args.get("--mesh"));
  const Drag drag = read_handles(args.get("--handles"), read_indices(args.get("--roi"), mesh.num_vertices(), "ROI"));
  const LaplacianWeights w = weights == "cotan" ? LaplacianWeights::Cotangent : LaplacianWeights::Uniform;

  std::unique_ptr<Deformer> d;
  ImplicitLaplacianDeformer* implicit = nullptr;
  if (method == "naive") d = std::make_unique<NaiveLaplacianDeformer>(mesh, NaiveOptions{w});
  if (method == "arap") {
    ArapOptions o;
    o.max_iterations = static_cast<int>(args.get_int("--iterations", 10, 1, 1000000));
    d = std::make_unique<ArapDeformer>(mesh, o);
  }
  if (method == "implicit") {
    ImplicitOptions o;
    o.weights = w;
    if (args.has("--scale-features")) o.shearing = ShearingRemoval::ScaleFeatures;
    auto p = std::make_unique<ImplicitLaplacianDeformer>(mesh, o);
    implicit = p.get();
    d = std::move(p);
  }
  using clock = std::chrono::steady_clock;
  auto ms = [](clock::time_point t0) { return std::chrono::duration<double, std::milli>(clock::now() - t0).count(); };
  d->set_selection(drag.selection);
  auto t0 = clock::now();
  d->precompute();
  const double setup_ms = ms(t0);
  geometry::TriMesh result = mesh;
  std::vector<double> frame_ms;
  for (const HandleTransforms& t : drag.frames) {
    t0 = clock::now();
    result.V = d->deform(t);
    frame_ms.push_back(ms(t0));
  }
  geometry::write_mesh(out_path, result);

  const Distortion q = distortion(mesh, result.V);
  json r = {{"method", method},
            {"weights", weights},
            {"vertices", mesh.num_vertices()},
            {"frames", frame_ms.size()},
            {"setup_s", setup_ms / 1000},
            {"frame_ms", frame_ms},
            {"distortion",
             {{"edge_length", summary(q.edge_length)},
              {"laplacian_length", summary(q.laplacian_length)},
              {"angle", summary(q.angle)},
              {"arap_energy", q.arap_energy}}}};
  if (implicit) r["degenerate_vertices"] = implicit->stats().degenerate_vertices;
  const std::string text = r.dump(2);
  std::printf("%s\n", text.c_str());
  if (args.has("--report"))
    geometry::write_file_atomically(args.get("--report"), [&](std::ostream& o) { o << text << "\n"; });
  return 0;
}

}  // namespace

extern const Command kDeformCommand = {"deform", "drag handles of a mesh: implicit Laplacian, naive Laplacian or ARAP", kUsage, run};

}  // namespace lapis::cli
