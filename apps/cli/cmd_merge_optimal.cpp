// `lapis merge --mode optimal`: the optimal merging boundary (thesis §3.4) headless — the
// boundary search, the merge along it and, for comparison, along the user's rough boundary.
#include <cmath>
#include <numbers>
#include <sstream>

#include "cli_io.h"
#include "lapis/core/checked_number.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "lapis/mesh_merge/regions_file.h"
#include "merge_report.h"

namespace lapis::cli {
namespace {

// "SCALE,DEGREES,U,V".
mesh_merge::Placement2D parse_placement(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  if (parts.size() != 4) throw UsageError("--placement must be SCALE,DEGREES,U,V, got '" + text + "'");
  mesh_merge::Placement2D p;
  p.scale = parse_finite<UsageError>(parts[0], "--placement scale", 1e-300, 1e300);
  p.angle = parse_finite<UsageError>(parts[1], "--placement rotation") * std::numbers::pi / 180;
  p.offset = {parse_finite<UsageError>(parts[2], "--placement u"), parse_finite<UsageError>(parts[3], "--placement v")};
  return p;
}

nlohmann::json boundary_json(const mesh_merge::OptimalBoundary& b) {
  nlohmann::json iterations = nlohmann::json::array();
  for (const mesh_merge::BoundaryIteration& it : b.history) {
    nlohmann::json j = {{"energy", it.energy},
                        {"scale", it.transform.s},
                        {"loop_vertices", it.loop_vertices},
                        {"loop_length", it.loop_length},
                        {"ms", it.ms}};
    if (std::isfinite(it.step_energy)) j["step_energy"] = it.step_energy;
    iterations.push_back(std::move(j));
  }
  const mesh_merge::BoundaryIteration& best = b.history[b.best_iteration];
  return {{"energy", b.energy},
          {"user_energy", b.user_energy},
          {"loop_vertices", b.loop.size()},
          {"loop_length", best.loop_length},
          {"user_loop_vertices", b.user_loop.size()},
          {"user_loop_length", b.history.front().loop_length},
          {"best_iteration", b.best_iteration},
          {"stopped_by", b.stopped_by},
          {"iterations", std::move(iterations)},
          {"timings_ms",
           {{"fill", b.timings.fill_ms},
            {"lscm", b.timings.lscm_ms},
            {"cut", b.timings.cut_ms},
            {"map", b.timings.map_ms},
            {"iterate", b.timings.iterate_ms}}}};
}

nlohmann::json merge_json(const mesh_merge::BoundaryOptimizer& optimizer, const mesh_merge::MergeResult& r) {
  const geometry::TriMesh &source = optimizer.source(), &target = optimizer.target();
  return {{"vertices", r.mesh.num_vertices()},
          {"faces", r.mesh.num_faces()},
          {"source_part_vertices", r.roi_vertices},
          {"boundary_refine_levels", r.refine_levels},
          {"timings_ms", {{"setup", r.timings.setup_ms}, {"solve", r.timings.solve_ms}, {"total", r.timings.total_ms}}},
          {"seam", seam_json(mesh_merge::seam_quality(target, r))},
          {"detail", detail_json(mesh_merge::detail_preservation(source, r))},
          {"feature_distortion",
           mesh_merge::feature_distortion(source, r, geometry::vertices_of_faces(source, optimizer.feature_faces()))}};
}

}  // namespace

int run_optimal_merge(const Args& args) {
  args.allow_only({"--source", "--target", "--regions", "--out", "--mode", "--placement", "--max-iterations",
                   "--smooth", "--feature", "--report"});
  const std::string out = args.get("--out");
  const geometry::TriMesh source = read_valid_mesh(args.get("--source"));
  const geometry::TriMesh target = read_valid_mesh(args.get("--target"));
  const mesh_merge::BoundaryRegions regions = mesh_merge::read_regions_file(args.get("--regions"), source, target);
  mesh_merge::OptimalBoundaryOptions options;
  options.max_iterations = static_cast<int>(args.get_int("--max-iterations", options.max_iterations, 0, 100000));
  mesh_merge::MergeOptions merge;
  merge.smooth_iterations = static_cast<int>(args.get_int("--smooth", merge.smooth_iterations, 0, 1000));
  const std::string feature = args.get("--feature", "held");
  if (feature != "held" && feature != "free") throw UsageError("--feature must be held or free, got '" + feature + "'");
  merge.hold_feature = feature == "held";

  const mesh_merge::BoundaryOptimizer optimizer(source, target, regions, options);
  const mesh_merge::Placement2D placement =
      args.has("--placement") ? parse_placement(args.get("--placement")) : optimizer.suggested_placement();
  const mesh_merge::OptimalBoundary b = optimizer.optimize(placement);
  const mesh_merge::MergeResult optimal = optimizer.merge(b, merge);
  const mesh_merge::MergeResult user = optimizer.merge(b, merge, true);

  nlohmann::json j = {{"mode", "optimal"},
                      {"out", out},
                      {"placement",
                       {{"scale", placement.scale},
                        {"degrees", placement.angle * 180 / std::numbers::pi},
                        {"u", placement.offset.x()},
                        {"v", placement.offset.y()}}},
                      {"feature", feature},
                      {"fill_is_fan", optimizer.fill_is_fan()},
                      {"cut_vertices", optimizer.cut().size()},
                      {"boundary", boundary_json(b)},
                      {"optimal_merge", merge_json(optimizer, optimal)},
                      {"user_boundary_merge", merge_json(optimizer, user)}};
  require_finite_numbers(j, "report");  // before the mesh is written: all outputs or none
  core::AtomicFileGroup outputs;
  geometry::write_mesh(out, optimal.mesh);
  emit_report(j, args);
  outputs.commit();
  return report_invalid_seam(mesh_merge::seam_quality(target, optimal));
}

}  // namespace lapis::cli
