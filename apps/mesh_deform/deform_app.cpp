// The deform app's state: edits and their undo history, the engine requests and results, and
// the files (open mesh, save / open selection, export).
#include "deform_app.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>

#include "lapis/core/atomic_file.h"
#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/selection_io.h"
#include "lapis/mesh_deform/vertex_distortion.h"
#include "lapis/viewer/colormap.h"

namespace lapis::deform_app {

const char* tool_name(Tool t) {
  switch (t) {
    case Tool::Move:
      return "move (gizmo)";
    case Tool::Brush:
      return "brush";
    case Tool::Lasso:
      return "lasso";
    case Tool::Connected:
      return "connected";
    case Tool::Geodesic:
      return "geodesic";
    case Tool::Pair:
      return "pair (transfer)";
  }
  return "?";
}

namespace {

EditState initial_state(int num_vertices) {
  EditState s;
  s.labels = std::make_shared<const VertexLabels>(num_vertices);
  return s;
}

// Appends the raw bytes of a value: requests compare equal exactly when nothing changed.
template <class T>
void append_bytes(std::string& key, const T& value) {
  key.append(reinterpret_cast<const char*>(&value), sizeof value);
}

}  // namespace

DeformApp::DeformApp(geometry::TriMesh mesh, DeformPaths paths, MethodSettings settings, bool preview_while_dragging)
    : rest_(std::move(mesh)),
      conn_(std::make_unique<geometry::Connectivity>(rest_)),
      paths_(std::move(paths)),
      settings_(settings),
      preview_while_dragging_(preview_while_dragging),
      state_(initial_state(rest_.num_vertices())),
      history_(state_),
      shown_(rest_),
      engine_(std::make_shared<EngineSlot>(rest_)) {
  mark_saved();
  fill_file_fields();
}

DeformApp::~DeformApp() = default;

void DeformApp::on_start(viewer::Viewer& v) {
  v.set_default_screenshot(paths_.screenshot);
  worker_.set_on_done([&v] { v.wake(); });  // a finished solve: redraw now
  transfer_worker_.set_on_done([&v] { v.wake(); });
  now_ = v.time();
  update_surface(v);
  v.frame_scene();
  labels_changed();
  if (load_on_start_) load_selection(v);
  if (!transfer_target_on_start_.empty()) open_transfer_target(v, transfer_target_on_start_);
}

bool DeformApp::busy() const {
  if (pending_export_ || frame_ - result_frame_ < 3) return true;
  if (transfer_worker_.busy() || transfer_received_ != transfer_submitted_) return true;
  return worker_.busy() || (selection_ && received_ != submitted_);
}

// ---------------------------------------------------------------- edits

void DeformApp::commit(std::string label) { history_.push(state_, std::move(label)); }

void DeformApp::set_labels(std::shared_ptr<const VertexLabels> labels, const std::string& label) {
  state_.labels = std::move(labels);
  const int handles = state_.labels->handle_count();
  if (static_cast<int>(state_.transforms.size()) < handles)
    state_.transforms.resize(static_cast<size_t>(handles), Eigen::Matrix4d::Identity());
  commit(label);
  labels_changed();
}

void DeformApp::labels_changed() {
  ++selection_revision_;
  surface_dirty_ = markers_dirty_ = true;
  try {
    selection_ = to_selection(*state_.labels);
    selection_error_.clear();
    if (state_.active_handle >= state_.labels->handle_count() || !state_.labels->any(state_.active_handle))
      state_.active_handle = selection_->handle_label.front();
  } catch (const Error& e) {
    selection_.reset();
    selection_error_ = e.what();
  }
  update_roi_warning();
  transfer_source_changed();
}

void DeformApp::undo(viewer::Viewer& v) { step_history(v, false); }
void DeformApp::redo(viewer::Viewer& v) { step_history(v, true); }

void DeformApp::step_history(viewer::Viewer& v, bool forward) {
  if (forward ? !history_.can_redo() : !history_.can_undo())
    return v.flash(forward ? "nothing to redo" : "nothing to undo");
  v.flash((forward ? "redo " : "undo ") + (forward ? history_.redo_label() : history_.undo_label()));
  const auto before = state_.labels;
  state_ = forward ? history_.redo() : history_.undo();
  if (before != state_.labels) labels_changed();  // a handle move keeps the selection (and its setup)
  markers_dirty_ = true;
}

void DeformApp::reset_pose(viewer::Viewer&) {
  for (auto& T : state_.transforms) T.setIdentity();
  commit("reset pose");
}

Eigen::Matrix4d& DeformApp::active_transform() {
  const size_t h = static_cast<size_t>(std::max(0, state_.active_handle));
  if (state_.transforms.size() <= h) state_.transforms.resize(h + 1, Eigen::Matrix4d::Identity());
  return state_.transforms[h];
}

Eigen::Vector3d DeformApp::handle_rest_centroid(int label) const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (size_t v = 0; v < state_.labels->label.size(); ++v)
    if (state_.labels->label[v] == label) sum += rest_.V.row(static_cast<Eigen::Index>(v)).transpose(), ++n;
  return n ? Eigen::Vector3d(sum / n) : Eigen::Vector3d::Zero();
}

void DeformApp::new_handle() {
  state_.active_handle = state_.labels->handle_count();
  if (state_.transforms.size() <= static_cast<size_t>(state_.active_handle))
    state_.transforms.resize(static_cast<size_t>(state_.active_handle) + 1, Eigen::Matrix4d::Identity());
  target_ = 0;
}

// ---------------------------------------------------------------- engine

void DeformApp::request_solve() {
  if (!selection_) return;
  LiveRequest r;
  r.settings = settings_;
  r.selection = selection_->selection;
  r.selection_revision = selection_revision_;
  for (int label : selection_->handle_label)
    r.transforms.regions.push_back(state_.transforms[static_cast<size_t>(label)]);
  r.preview = dragging_ && preview_while_dragging_;
  if (color_mode_ == ColorMode::Distortion) r.field = field_;
  if (settings_.method == Method::Salient && features_edited_) {
    r.settings.salient.user_features = FeatureMerge::Replace;  // the painted ones are the features
    r.features = features_.features();
  }
  r.features_revision = features_revision_;

  std::string key;
  append_bytes(key, epoch_);
  append_bytes(key, selection_revision_);
  append_bytes(key, settings_.method);
  append_bytes(key, settings_.weights);
  append_bytes(key, settings_.scale_features);
  append_bytes(key, settings_.arap_iterations);
  // Field by field: the options struct has padding, whose bytes are not part of its value.
  const EdgeLaplacianOptions& e = settings_.edge;
  for (int v :
       {static_cast<int>(e.domain), static_cast<int>(e.weights), static_cast<int>(e.transform),
        static_cast<int>(e.frame), e.iterations, static_cast<int>(e.warm_start), static_cast<int>(e.soft_handles)})
    append_bytes(key, v);
  append_bytes(key, e.tolerance);
  append_bytes(key, e.handle_weight);
  const SalientOptions& sa = settings_.salient;
  for (int v : {sa.iterations, sa.subspace_vertices, static_cast<int>(sa.detect_features), sa.detection.hks.eigenpairs,
                static_cast<int>(sa.warm_start)})
    append_bytes(key, v);
  append_bytes(key, features_revision_);
  append_bytes(key, r.preview);
  for (const auto& T : r.transforms.regions) key.append(reinterpret_cast<const char*>(T.data()), sizeof(double) * 16);
  // The colour mode is not part of the key: a new colouring of the same frame is no reason to
  // solve again (ARAP would go on iterating and change the shape).
  if (key != solve_key_) {
    solve_key_ = key;
    arap_round_ = 0;
    arap_energy_ = -1;
    convergence_.clear();
  }
  append_bytes(key, arap_round_);
  if (key == last_key_) return request_recolor();
  last_key_ = key;

  // The progress indicator: shown while a request that needs a new setup is running.
  const bool needs_setup =
      !last_ || last_->epoch != epoch_ || !(last_->settings == settings_) || last_->revision != selection_revision_;
  if (needs_setup && setup_started_ < 0) setup_started_ = now_;
  const std::uint64_t id = ++submitted_, epoch = epoch_, revision = selection_revision_;
  auto slot = engine_;
  auto selection = std::make_shared<const Selection>(r.selection);
  const MethodSettings settings = settings_;
  worker_.submit([slot, r = std::move(r), id, epoch, revision, selection, settings] {
    Solved s;
    s.request = id;
    s.epoch = epoch;
    s.revision = revision;
    s.selection = selection;
    s.settings = settings;
    s.field = r.field;
    s.frame = slot->live.update(r);
    return s;
  });
}

void DeformApp::request_recolor() {
  const std::optional<DistortionField> wanted =
      color_mode_ == ColorMode::Distortion ? std::optional<DistortionField>(field_) : std::nullopt;
  // Only for the newest frame, solved and shown, when it measures something else.
  if (!wanted || !last_ || last_->epoch != epoch_ || last_->request != submitted_ || received_ != submitted_ ||
      last_->field == wanted)
    return;
  Solved s = *last_;
  s.request = ++submitted_;
  s.recolor = true;
  s.field = wanted;
  auto slot = engine_;
  worker_.submit([slot, s = std::move(s)]() mutable {
    s.frame.distortion = vertex_distortion(slot->live.rest(), s.frame.positions, *s.field);
    return s;
  });
}

void DeformApp::continue_arap() {
  const double energy = last_->frame.energy;
  const double decrease = arap_energy_ < 0 ? 1.0 : (arap_energy_ - energy) / std::max(arap_energy_, 1e-300);
  arap_energy_ = energy;
  char buf[160];
  if (decrease <= kArapRoundTolerance || arap_round_ >= kArapMaxRounds) {
    std::snprintf(buf, sizeof buf, "ARAP %s after %d round(s) of %d iterations, energy %.4g",
                  decrease <= kArapRoundTolerance ? "converged" : "stopped", arap_round_ + 1,
                  last_->settings.arap_iterations, energy);
    convergence_ = buf;
    return;
  }
  ++arap_round_;  // the next request_solve() runs the round
  std::snprintf(buf, sizeof buf, "ARAP converging: round %d, energy %.4g", arap_round_ + 1, energy);
  convergence_ = buf;
}

void DeformApp::receive(viewer::Viewer& v) {
  std::optional<Solved> s;
  try {
    s = worker_.take();
  } catch (const Error& e) {
    // The newest request failed (a selection the deformer rejects): nothing more is coming.
    engine_error_ = e.what();
    received_ = submitted_;
    setup_started_ = -1;
    v.flash(std::string("deformation failed: ") + e.what(), viewer::Tone::Error);
    return;
  }
  if (!s || s->epoch != epoch_) return;  // nothing new, or from a mesh no longer open
  engine_error_.clear();
  received_ = s->request;
  if (s->recolor) {
    update_legend(s->frame.distortion);
    last_ = std::move(s);
    surface_dirty_ = true;
    return;
  }
  if (s->frame.did_setup) {
    setup_ms_.push_back(s->frame.setup_ms);
    isoline_field_ = s->frame.isoline_field;
    rigidity_ = s->frame.rigidity;
    isolines_ = s->frame.isolines;
  }
  if (s->revision == selection_revision_ && s->settings == settings_) setup_started_ = -1;
  solve_ms_.push_back(s->frame.solve_ms);
  // The full solve after a drag's previews: say how far the shape moved from the last one shown.
  if (last_ && last_->frame.preview && !s->frame.preview && s->frame.method == "implicit" &&
      last_->revision == s->revision && last_->frame.positions.rows() == s->frame.positions.rows()) {
    const double diagonal = (rest_.V.colwise().maxCoeff() - rest_.V.colwise().minCoeff()).norm();
    preview_gap_ = (s->frame.positions - last_->frame.positions).rowwise().norm().maxCoeff() / diagonal;
  }
  shown_.V = s->frame.positions;
  features_received(s->frame);
  update_legend(s->frame.distortion);
  last_ = std::move(s);
  result_frame_ = v.frame();
  pick_stale_ = true;
  surface_dirty_ = markers_dirty_ = true;
  // ARAP goes on iterating on the pose once the user lets go, until the energy settles.
  if (last_->frame.energy >= 0 && !last_->frame.preview && last_->request == submitted_ && !dragging_) continue_arap();
}

void DeformApp::update_legend(const Eigen::VectorXd& distortion) {
  if (legend_fixed_)
    legend_hi_ = legend_max_;
  else if (distortion.size() > 0)
    legend_hi_ = std::max(1e-6, viewer::percentile(distortion, 0.95));
}

// The detected features seed the painted ones until the user edits them.
void DeformApp::features_received(const LiveFrame& f) {
  if (f.method != "salient" || features_edited_) return;
  features_.seed(f.features, rest_.num_vertices());
  active_feature_ = std::min(active_feature_, std::max(0, features_.count));
}

void DeformApp::on_frame(viewer::Viewer& v) {
  now_ = v.time();
  frame_ = v.frame();
  receive(v);
  request_solve();  // no-op unless something changed
  receive_transfer(v);
  request_transfer();
  if (pending_export_ && export_ready()) export_result(v);
  if (surface_dirty_) update_surface(v);
  if (markers_dirty_) update_markers(v);
  if (target_dirty_ && pairing_) update_target_surface(v);
  update_gizmo(v);
}

void DeformApp::on_exit(viewer::Viewer& v) {
  worker_.set_on_done({});  // the window goes away after this
  transfer_worker_.set_on_done({});
  if (paths_.export_on_exit) {
    // Batch runs: let the newest request finish so the export holds it, and what it asks for
    // next (the full pipeline after a drag preview, ARAP's rounds to convergence).
    for (;;) {
      worker_.wait();
      receive(v);
      const std::uint64_t before = submitted_;
      request_solve();
      if (submitted_ == before) break;
    }
    request_transfer();
    transfer_worker_.wait();
    receive_transfer(v);
    pending_export_ = true;
    if (!export_ready()) {
      std::fprintf(stderr, "lapis-deform: nothing to export (%s)\n",
                   !selection_error_.empty() ? selection_error_.c_str() : engine_error_.c_str());
      exit_status_ = 1;
    } else if (!export_result(v)) {
      exit_status_ = 1;
    }
    pending_export_ = false;
  }
}

void DeformApp::benchmark_fields(nlohmann::json& j) const {
  j["app"] = "lapis-deform";
  j["vertices"] = rest_.num_vertices();
  j["method"] = method_info(settings_.method).name;
  j["weights"] = to_string(settings_.weights);
  j["preview_while_dragging"] = preview_while_dragging_;
  j["solve_ms"] = solve_ms_;
  j["setup_ms"] = setup_ms_;
  j["requests"] = submitted_;
  j["solved"] = solve_ms_.size();
  j["stale_dropped"] = submitted_ - solve_ms_.size();
  j["drag_events"] = drag_frames_;
  if (!solve_ms_.empty()) {
    std::vector<double> s = solve_ms_;
    std::sort(s.begin(), s.end());
    j["solve_ms_median"] = s[s.size() / 2];
    j["solve_ms_max"] = s.back();
  }
  if (last_) j["degenerate_vertices"] = last_->frame.degenerate_vertices.size();
}

// ---------------------------------------------------------------- files

void DeformApp::open_mesh(viewer::Viewer& v, const fs::path& path) {
  try {
    geometry::TriMesh mesh = geometry::read_mesh(path);
    auto conn = std::make_unique<geometry::Connectivity>(mesh);
    if (pairing_) close_transfer_target(v);  // its pairs were made on the old mesh
    rest_ = std::move(mesh);
    conn_ = std::move(conn);
    paths_ = paths_beside(path, paths_);
    fill_file_fields();
    v.set_default_screenshot(paths_.screenshot);
    // Jobs still running hold the old slot (and read the old mesh only through it, which
    // they copied): a new slot and epoch make their results stale.
    engine_ = std::make_shared<EngineSlot>(rest_);
    ++epoch_;
    last_.reset();
    features_ = {};  // a new mesh's features come from its own detection
    features_edited_ = false;
    ++features_revision_;
    last_key_.clear();
    received_ = submitted_;
    state_ = initial_state(rest_.num_vertices());
    history_.reset(state_);
    mark_saved();
    shown_ = rest_;
    pick_bvh_.reset();
    pick_stale_ = true;
    labels_changed();
    update_surface(v);
    v.frame_scene();
    v.flash("opened " + path.string() + " (" + std::to_string(rest_.num_vertices()) + " vertices)",
            viewer::Tone::Success);
    if (fs::exists(paths_.roi)) load_selection(v);  // its own selection, saved last time
  } catch (const Error& e) {
    v.flash(std::string("open failed: ") + e.what(), viewer::Tone::Error);
  }
}

void DeformApp::save_selection(viewer::Viewer& v) {
  if (!selection_) return v.flash("save selection: " + selection_error_, viewer::Tone::Error);
  try {
    for (const auto* p : {&paths_.roi, &paths_.handles}) core::create_parent_directories(*p);
    HandleTransforms now;
    for (int label : selection_->handle_label) now.regions.push_back(state_.transforms[static_cast<size_t>(label)]);
    write_roi(paths_.roi, selection_->selection.roi);
    write_handles(paths_.handles, selection_->selection, {now});
    mark_saved();
    v.flash("saved " + paths_.roi.string() + " and " + paths_.handles.string(), viewer::Tone::Success);
  } catch (const Error& e) {
    v.flash(std::string("save failed: ") + e.what(), viewer::Tone::Error);
  }
}

void DeformApp::load_selection(viewer::Viewer& v) {
  try {
    Drag drag = read_handles(paths_.handles);
    drag.selection.roi = read_roi(paths_.roi);
    // The deformer's own rules (handles inside the ROI, no duplicates, indices in range), so a
    // file the CLI would reject is rejected here too, with the same message.
    (void)make_layout(drag.selection, rest_.num_vertices(), "mesh_deform::Deformer::precompute()");
    auto labels = std::make_shared<VertexLabels>(from_selection(drag.selection, rest_.num_vertices()));
    // The handles' last frame is their pose; point handles become translated region handles.
    const HandleTransforms& last = drag.frames.back();
    std::vector<Eigen::Matrix4d> transforms = last.regions;
    for (const auto& t : last.points) {
      Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
      T.topRightCorner<3, 1>() = t;
      transforms.push_back(T);
    }
    state_.transforms = std::move(transforms);
    state_.active_handle = 0;
    set_labels(std::move(labels), "open selection");
    mark_saved();
    v.flash("opened " + paths_.roi.string() + " and " + paths_.handles.string(), viewer::Tone::Success);
  } catch (const Error& e) {
    v.flash(std::string("open selection failed: ") + e.what(), viewer::Tone::Error);
  }
}

bool DeformApp::export_ready() const {
  // The newest request solved, by the full pipeline (not a drag preview).
  return last_ && !worker_.busy() && received_ == submitted_ && last_->request == submitted_ && !last_->frame.preview &&
         transfer_ready();
}

bool DeformApp::export_result(viewer::Viewer& v) {
  pending_export_ = false;
  if (!export_ready()) {
    if (!selection_) return v.flash("export: " + selection_error_, viewer::Tone::Error), false;
    if (!engine_error_.empty()) return v.flash("export: " + engine_error_, viewer::Tone::Error), false;
    pending_export_ = true;  // written once the newest solve arrives
    return v.flash("export: waiting for the solve to finish"), false;
  }
  try {
    const fs::path& out = paths_.export_mesh;
    core::create_parent_directories(out);
    const fs::path stem = out.parent_path() / out.stem();
    geometry::TriMesh result = rest_;
    result.V = last_->frame.positions;
    core::AtomicFileGroup files;  // the mesh and the files that reproduce it: all new or all old
    geometry::write_mesh(out, result);
    // What `lapis deform` needs to reproduce the export: the selection and every frame this
    // setup solved (the implicit method unwraps rotations over them, ARAP warm-starts).
    const fs::path roi = stem.string() + ".roi.txt", handles = stem.string() + ".handles.json";
    write_roi(roi, last_->selection->roi);
    write_handles(handles, *last_->selection, last_->frame.history);
    const MethodSettings& s = last_->settings;
    const bool edge = s.method == Method::Edge, iso = s.method == Method::Isolines;
    const LaplacianWeights weights = edge ? s.edge.weights : s.weights;
    const int iterations = edge                          ? s.edge.iterations
                           : iso                         ? s.isolines.max_iterations
                           : s.method == Method::Salient ? s.salient.iterations
                                                         : s.arap_iterations;
    std::string command = "lapis deform --mesh " + paths_.mesh.string() + " --roi " + roi.string() + " --handles " +
                          handles.string() + " --method " + method_info(s.method).name + " --weights " +
                          to_string(weights) + (s.scale_features ? " --scale-features" : "") + " --iterations " +
                          std::to_string(iterations);
    if (edge)
      command += std::string(" --domain ") + to_string(s.edge.domain) + " --transform " + to_string(s.edge.transform) +
                 " --frame " + to_string(s.edge.frame) + (s.edge.warm_start ? " --warm-start" : "");
    if (iso)
      command += " --isolines " + std::to_string(s.isolines.isolines) + " --solve " + to_string(s.isolines.solve) +
                 " --fit " + to_string(s.isolines.fit);
    command += " --out OUT.obj";
    nlohmann::json j = {{"mesh", paths_.mesh.string()},
                        {"roi", roi.string()},
                        {"handles", handles.string()},
                        {"method", method_info(s.method).name},
                        {"weights", to_string(weights)},
                        {"scale_features", s.scale_features},
                        {"iterations", iterations},
                        {"frames", last_->frame.history.size()},
                        {"cli", command}};
    const bool transferred = export_transfer(stem, out, j);
    core::write_file_atomically(stem.string() + ".deform.json", [&](std::ostream& o) { o << j.dump(2) << "\n"; });
    files.commit();
    mark_saved();  // the export holds the selection and the pose too
    v.flash("exported " + out.string() + " (+ .roi.txt, .handles.json, .deform.json" +
                (transferred ? ", the transfer target" : "") + ")",
            viewer::Tone::Success);
    std::printf("exported %s\n", out.string().c_str());
    return true;
  } catch (const Error& e) {
    v.flash(std::string("export failed: ") + e.what(), viewer::Tone::Error);
    std::fprintf(stderr, "lapis-deform: export failed: %s\n", e.what());
    return false;
  }
}

}  // namespace lapis::deform_app
