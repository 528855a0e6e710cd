// Exports of lapis-merge (Ctrl+E, File menu, --export on exit): the merged mesh and everything
// `lapis merge` needs to produce the same mesh from files — the source as placed, the target,
// the pairs file (the regions file in the optimal-boundary mode), the handles file in dependent
// mode — plus that command line, so an
// interactive result can be reproduced and checked headless.
#include <charconv>
#include <cstdio>

#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_merge/pairs_file.h"
#include "lapis/mesh_merge/regions_file.h"
#include "merge_app.h"

namespace lapis::merge_app {
namespace {

std::string shortest(double x) {  // round-trips, so the command reproduces the option exactly
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace

bool MergeApp::export_all(viewer::Viewer& v) {
  export_pending_ = false;
  auto refuse = [&](const std::string& why) {
    v.flash(why, viewer::Tone::Error);
    std::fprintf(stderr, "lapis-merge: %s\n", why.c_str());
    return false;
  };
  if (!last_ || last_->revision != revision()) return refuse("export: no merge of the current setup");
  if (!last_->error.empty()) return refuse("export: nothing to export, the merge failed: " + last_->error);
  const std::string p = paths_.export_prefix.string();
  const std::string merged = p + ".obj", source = p + "_source.obj", target = p + "_target.obj",
                    pairs = p + "_pairs.json", handles = p + "_handles.json", command = p + "_command.txt";
  try {
    core::create_parent_directories(paths_.export_prefix);
    const MergeSetup& s = setup();
    core::AtomicFileGroup files;  // the merge and the files that reproduce it: all new or all old
    geometry::write_mesh(merged, last_->result.mesh);
    geometry::write_mesh(source, mesh_merge::placed_source(s));
    geometry::write_mesh(target, *s.target);
    std::string cmd;
    if (s.options.mode == mesh_merge::MergeMode::OptimalBoundary) {
      const std::string regions = p + "_regions.json";
      const mesh_merge::Placement2D q = current_placement();
      mesh_merge::write_regions_file(regions, mesh_merge::boundary_regions(s));
      cmd = "lapis merge --mode optimal --source " + source + " --target " + target + " --regions " + regions +
            " --placement " + shortest(q.scale) + "," + shortest(q.angle * 180 / 3.141592653589793) + "," +
            shortest(q.offset.x()) + "," + shortest(q.offset.y()) + " --out " + merged + " --smooth " +
            std::to_string(s.options.smooth_iterations) + (s.options.hold_feature ? "" : " --feature free");
    } else {
      mesh_merge::write_pairs_file(pairs, mesh_merge::loop_pairs(s));
      cmd = "lapis merge --source " + source + " --target " + target + " --pairs " + pairs + " --out " + merged +
            " --smooth " + std::to_string(s.options.smooth_iterations);
    }
    if (s.options.mode == mesh_merge::MergeMode::Dependent) {
      mesh_merge::write_handles_file(handles, s.options.handles);
      cmd += " --mode dependent --handles " + handles + " --roi-width " + shortest(s.options.roi_width);
    } else if (s.options.mode == mesh_merge::MergeMode::Transition) {
      const auto& t = s.options.transition;
      cmd += " --mode transition --source-width " + shortest(t.source_width) + " --target-width " +
             shortest(t.target_width) + " --keep " +
             (t.keep == mesh_merge::TransitionKeep::Source ? "source" : "target");
      if (t.configuration_dependent) {
        mesh_merge::write_handles_file(handles, s.options.handles);
        cmd +=
            " --transition-boundary dependent --handles " + handles + " --roi-width " + shortest(s.options.roi_width);
      }
    }
    if (!s.options.features.empty()) {
      const std::string features = p + "_features.json";
      mesh_merge::write_features_file(features, s.options.features);
      cmd += " --features " + features;
    }
    core::write_file_atomically(command, [&](std::ostream& out) { out << cmd << "\n"; });
    files.commit();
    const std::string inputs = s.options.mode == mesh_merge::MergeMode::OptimalBoundary ? p + "_regions.json" : pairs;
    v.flash("exported " + merged + " and " + inputs, viewer::Tone::Success);
    std::printf("exported %s, %s, %s, %s\n", merged.c_str(), source.c_str(), target.c_str(), inputs.c_str());
    return true;
  } catch (const Error& e) {
    return refuse(std::string("export failed: ") + e.what());
  }
}

}  // namespace lapis::merge_app
