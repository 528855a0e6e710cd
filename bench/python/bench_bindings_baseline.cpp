// The C++ side of bench_bindings.py: the same deform frames and hair edits as the Python side
// runs through `import lapis`, driven line by line from stdin so that the two sides alternate
// call by call and a slow spell of this shared machine falls on both.
//   bench_bindings_baseline deform MESH LOOP_LEVELS METHOD ROI HANDLES
//   bench_bindings_baseline hair SESSION GRID_UNKNOWNS ROOTS FIELD_METHOD STROKE
// Prints "ready" after the set-up, then one line of JSON per command:
//   deform: "frame K" → {"ms": ...}, the handles file's frame K deformed as a C++ caller would;
//   hair:   "stroke" → {"ms": ...}, the stroke (STROKE: a JSON array of points) added and the
//           hairstyle updated (LiveHairstyle, strands regrown into the last ones' storage);
//           "unstroke" → {"ms": ...}, the stroke removed and the hairstyle updated;
//   "save PATH" → {} after writing the last result (deform: the mesh, exact; hair: .hair).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lapis/core/error.h"
#include "lapis/geometry/camera.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/hair_sketch/hair_file.h"
#include "lapis/hair_sketch/live_hairstyle.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/mesh_deform/selection_io.h"

using namespace lapis;

namespace {

// Answers each command line of stdin with `run(command)`'s JSON, after "ready".
void serve(const std::function<nlohmann::json(const std::string&)>& run) {
  std::printf("ready\n");
  std::fflush(stdout);
  for (std::string line; std::getline(std::cin, line) && line != "quit";) {
    std::printf("%s\n", run(line).dump().c_str());
    std::fflush(stdout);
  }
}

double ms_of(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int serve_deform(char** argv) {
  geometry::TriMesh mesh = geometry::loop_subdivide(geometry::read_mesh(argv[0]), std::stoi(argv[1]));
  mesh_deform::MethodSettings settings;
  settings.method = mesh_deform::method_from_name(argv[2]);
  mesh_deform::Drag drag = mesh_deform::read_handles(argv[4]);
  drag.selection.roi = mesh_deform::read_roi(argv[3]);
  const geometry::Faces faces = mesh.F;
  auto d = mesh_deform::make_deformer(std::move(mesh), settings);
  d->set_selection(drag.selection);
  d->precompute();
  geometry::Vertices last;
  serve([&](const std::string& cmd) -> nlohmann::json {
    if (cmd.rfind("frame ", 0) == 0) {
      const auto& frame = drag.frames.at(std::stoul(cmd.substr(6)));
      return {{"ms", ms_of([&] { last = d->deform(frame); })}};
    }
    geometry::write_mesh(cmd.substr(5), geometry::TriMesh{last, faces});
    return nlohmann::json::object();
  });
  return 0;
}

int serve_hair(char** argv) {
  using namespace hair_sketch;
  Hairstyle style = load_session(argv[0]);
  style.settings.grid.target_unknowns = std::stod(argv[1]);
  style.settings.roots.count = std::stoi(argv[2]);
  style.settings.field_method =
      std::string(argv[3]) == "multigrid" ? hair_field::FieldMethod::Multigrid : hair_field::FieldMethod::Thesis;
  const Head head = load_session_head(style, argv[0]);
  style = replay_strokes(style, head);
  StylePrimitive stroke;  // as lapis.HairSession.add_stream_curve() makes it
  StreamCurve curve;
  std::ifstream in(argv[4]);
  for (const auto& p : nlohmann::json::parse(in)) curve.points.emplace_back(p[0], p[1], p[2]);
  stroke.shape = curve;
  stroke.viewpoint = geometry::eye_position(style.camera);
  stroke.support = style.settings.support;
  LiveHairstyle live(head, style.settings);
  Strands strands = live.update(style.primitives).strands;
  serve([&](const std::string& cmd) -> nlohmann::json {
    if (cmd == "stroke" || cmd == "unstroke") {
      return {{"ms", ms_of([&] {
                 if (cmd == "stroke")
                   style.primitives.push_back(stroke);
                 else
                   style.primitives.pop_back();
                 strands = live.update(style.primitives, std::move(strands)).strands;
               })}};
    }
    write_hair_file(cmd.substr(5), to_hair_file(strands));
    return nlohmann::json::object();
  });
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::string job = argc > 1 ? argv[1] : "";
    if (job == "deform" && argc == 7) return serve_deform(argv + 2);
    if (job == "hair" && argc == 7) return serve_hair(argv + 2);
    std::fprintf(stderr,
                 "usage: bench_bindings_baseline deform MESH LOOP_LEVELS METHOD ROI HANDLES\n"
                 "       bench_bindings_baseline hair SESSION GRID_UNKNOWNS ROOTS FIELD_METHOD STROKE\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_bindings_baseline: %s\n", e.what());
    return 1;
  }
}
