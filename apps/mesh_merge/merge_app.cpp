#include "merge_app.h"

#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bundled_meshes.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/viewer/picking.h"

namespace lapis::merge_app {

namespace {

constexpr double kPickPixels = 14.0;  // how near a click must be to a loop or vertex

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool same_options(const mesh_merge::MergeOptions& a, const mesh_merge::MergeOptions& b) {
  // What the Merger's precompute depends on (smoothing is set per merge).
  // Transition mode sets up everything in merge(), from the options the Merger holds.
  return a.mode == b.mode && a.roi_width == b.roi_width && a.handles == b.handles && a.refine_ratio == b.refine_ratio &&
         a.refine_levels == b.refine_levels && a.transition.source_width == b.transition.source_width &&
         a.transition.target_width == b.transition.target_width && a.transition.weight == b.transition.weight &&
         a.transition.keep == b.transition.keep &&
         a.transition.configuration_dependent == b.transition.configuration_dependent && a.features == b.features;
}

}  // namespace

double first_band_width(const mesh_merge::MergeSetup& s) {
  if (!s.target || !s.source) return 0.1;
  double w = 0;
  try {
    w = mesh_merge::suggested_transition_width(*s.source, *s.target, mesh_merge::loop_pairs(s));
  } catch (const Error&) {
  }
  return w > 0 ? w : 0.05 * std::max(1e-9, mesh_merge::bbox_diagonal(s.target->V));
}

const char* tool_name(Tool t) {
  switch (t) {
    case Tool::PairLoops:
      return "pair loops";
    case Tool::Keys:
      return "key correspondences";
    case Tool::Handles:
      return "fixed handles";
    case Tool::Move:
      return "move source";
    case Tool::Paint:
      return "paint & cut";
  }
  return "?";
}

MergeApp::MergeApp(MergeSetup setup, std::string source_name, std::string target_name, AppPaths paths)
    : history_(Snapshot{std::move(setup), std::move(source_name), std::move(target_name), 1}),
      paths_(std::move(paths)) {
  refresh_pickables();
}

MergeApp::~MergeApp() = default;

void MergeApp::on_start(viewer::Viewer& v) {
  v.set_default_screenshot(paths_.export_prefix.string() + "_screenshot.png");  // beside the exports
  worker_.set_on_done([&v] { v.wake(); });                                      // a finished merge: redraw now
  v.camera().yaw = kViewYaw;
  v.camera().pitch = kViewPitch;
  update_scene(v);
  frame(v);
}

// The panels take the right kPanelWidth pixels: fit and centre the meshes in what is left.
void MergeApp::frame(viewer::Viewer& v) {
  v.frame_scene();
  fit_beside_panels(v.camera(), v.width(), v.height());
}

bool MergeApp::busy() const {
  return worker_.busy() || export_pending_ ||
         (requested_revision_ == revision() && (!last_ || last_->revision != requested_revision_));
}

// ---------------------------------------------------------------- edits and history

void MergeApp::commit(viewer::Viewer&, MergeSetup next, std::string name) {
  history_.push(Snapshot{std::move(next), source_name(), target_name(), ++last_revision_}, std::move(name));
  refresh_pickables();
  scene_dirty_ = true;
}

void MergeApp::undo(viewer::Viewer& v) {
  if (!history_.can_undo()) return v.flash("nothing to undo");
  v.flash("undo: " + history_.undo_label());
  history_.undo();
  after_history_step();
}

void MergeApp::redo(viewer::Viewer& v) {
  if (!history_.can_redo()) return v.flash("nothing to redo");
  v.flash("redo: " + history_.redo_label());
  history_.redo();
  after_history_step();
}

void MergeApp::after_history_step() {
  refresh_pickables();
  clear_picks();  // half-made picks and paint index a mesh the step may have replaced
  painted_.clear();
  scene_dirty_ = true;
}

void MergeApp::clear_picks() {
  pending_source_loop_ = pending_target_loop_ = pending_key_source_ = pending_key_target_ = -1;
}

void MergeApp::refresh_pickables() {
  auto rebuild = [](PickableMesh& p, const std::shared_ptr<const geometry::TriMesh>& rest,
                    const Eigen::Matrix4d& placement, const MergeSetup& s, bool is_source) {
    if (p.rest == rest && p.placement == placement && p.conn) return;
    p.rest = rest;
    p.placement = placement;
    p.mesh = is_source ? mesh_merge::placed_source(s) : *rest;
    p.conn = std::make_unique<geometry::Connectivity>(p.mesh);
    p.bvh = std::make_unique<geometry::Bvh>(p.mesh);
  };
  rebuild(source_, setup().source, setup().placement, setup(), true);
  rebuild(target_, setup().target, Eigen::Matrix4d::Identity(), setup(), false);
}

void MergeApp::replace_meshes(viewer::Viewer& v, std::shared_ptr<const geometry::TriMesh> source,
                              std::string source_name, std::shared_ptr<const geometry::TriMesh> target,
                              std::string target_name, std::string edit, Placement placement) {
  MergeSetup next = setup();
  const bool new_source = source != next.source, new_meshes = new_source || target != next.target;
  if (new_source) next.options.handles.clear();  // vertex indices of the old source
  next.pairs.clear();                            // loop indices belong to the old meshes
  next.source = std::move(source);
  next.target = std::move(target);
  // An opened mesh arrives placed: the source sized to the target and beside it, not at its
  // own scale on top of it (a lion's head came in at ten times a man's size).
  if (new_meshes && placement == Placement::Suggested)
    next.placement = mesh_merge::suggest_placement(*next.source, *next.target);
  else if (new_source && placement == Placement::Identity)
    next.placement.setIdentity();
  // The old result belongs to the old meshes: off the screen until a merge of the new ones.
  if (new_meshes) shown_.reset(), last_.reset();
  history_.push(Snapshot{std::move(next), std::move(source_name), std::move(target_name), ++last_revision_},
                std::move(edit));
  refresh_pickables();
  clear_picks();
  painted_.clear();
  update_scene(v);
  if (placement != Placement::Keep) frame(v);
}

void MergeApp::load_mesh(viewer::Viewer& v, const std::filesystem::path& path, bool as_source) {
  try {
    auto mesh = std::make_shared<const geometry::TriMesh>(geometry::read_mesh(path));
    const std::string name = path.filename().string();
    if (as_source)
      replace_meshes(v, mesh, name, setup().target, target_name(), "open source " + name, Placement::Suggested);
    else
      replace_meshes(v, setup().source, source_name(), mesh, name, "open target " + name, Placement::Suggested);
  } catch (const Error& e) {
    v.flash(std::string("open failed: ") + e.what(), viewer::Tone::Error);
  }
}

void MergeApp::load_preset(viewer::Viewer& v, int preset) {
  try {
    MeshPair p = load_preset_meshes(preset, paths_.asset_dir);
    replace_meshes(v, p.source, p.source_name, p.target, p.target_name, "open preset");
    if (p.place_source) {
      MergeSetup next = setup();
      next.placement = mesh_merge::suggest_placement(*p.source, *p.target);
      commit(v, std::move(next), "place source");
      update_scene(v);
      frame(v);
    }
  } catch (const Error& e) {
    v.flash(std::string("open failed: ") + e.what(), viewer::Tone::Error);
  }
}

// ---------------------------------------------------------------- input

bool MergeApp::on_event(viewer::Viewer& v, const viewer::InputEvent& e) {
  using viewer::EventType;
  if (e.type == EventType::Key) return handle_key(v, e);
  if (e.type == EventType::MouseButton && e.button == GLFW_MOUSE_BUTTON_LEFT) {
    if (e.action == GLFW_PRESS) {
      if (tool_ == Tool::Move)
        press_move(v, e.x, e.y);
      else if (tool_ == Tool::Paint)
        press_paint(v, e.x, e.y, e.mods & GLFW_MOD_SHIFT);
      else
        click(v, e.x, e.y);
      return true;
    }
    if (e.action == GLFW_RELEASE && (drag_start_ || painting_)) {
      if (drag_start_) release_move(v);
      if (painting_ && optimal_mode()) end_region_stroke(v);
      painting_ = false;
      return true;
    }
  }
  if (e.type == EventType::MouseMove) {
    if (drag_start_) return drag_move(v, e.x, e.y), true;
    if (painting_) return drag_paint(v, e.x, e.y), true;
    if (tool_ == Tool::Move) gizmo_.hovered = gizmo_.hit(v.camera_matrices(), {e.x, e.y});
  }
  return false;
}

int MergeApp::pair_of_source_loop(int loop) const {
  for (size_t p = 0; p < setup().pairs.size(); ++p)
    if (setup().pairs[p].source_loop == loop) return static_cast<int>(p);
  return -1;
}

int MergeApp::pair_of_target_loop(int loop) const {
  for (size_t p = 0; p < setup().pairs.size(); ++p)
    if (setup().pairs[p].target_loop == loop) return static_cast<int>(p);
  return -1;
}

void MergeApp::click(viewer::Viewer& v, double x, double y) {
  switch (tool_) {
    case Tool::PairLoops:
      click_pair_loops(v, x, y);
      break;
    case Tool::Keys:
      click_keys(v, x, y);
      break;
    case Tool::Handles:
      click_handles(v, x, y);
      break;
    case Tool::Move:
    case Tool::Paint:
      break;  // drags, see on_event()
  }
  scene_dirty_ = true;
}

// Loops are drawn on top of the surfaces (update_loops), so a loop is picked wherever its line
// is drawn, hidden parts included; the source's only while the source is drawn. A click that
// misses keeps the half-made pair.
void MergeApp::click_pair_loops(viewer::Viewer& v, double x, double y) {
  show_inputs_to_pick(v);
  const auto cam = v.camera_matrices();
  const bool source_drawn = v.scene().meshes["source"].visible;
  const viewer::LoopPick s = source_drawn
                                 ? viewer::pick_loop(cam, source_.mesh.V, source_.loops(), x, y, kPickPixels, {})
                                 : viewer::LoopPick{};
  const viewer::LoopPick t = viewer::pick_loop(cam, target_.mesh.V, target_.loops(), x, y, kPickPixels, {});
  if (!s && !t) return v.flash("no boundary loop there: click near a loop (drawn as a line)");
  if (s && (!t || s.pixels <= t.pixels))
    pending_source_loop_ = s.loop;
  else
    pending_target_loop_ = t.loop;
  if (pending_source_loop_ < 0 || pending_target_loop_ < 0) return;
  MergeSetup next = setup();
  const int pair = mesh_merge::pair_loops(next, pending_source_loop_, pending_target_loop_);
  pending_source_loop_ = pending_target_loop_ = -1;
  // The new pair gets a suggested key right away; a key the user clicks replaces it.
  try {
    const mesh_merge::KeySuggestion s = mesh_merge::suggest_keys(next, source_.loops(), target_.loops(), pair).front();
    flash_suggestion(v, pair, s);
  } catch (const Error& e) {
    v.flash(std::string("no key suggested: ") + e.what(), viewer::Tone::Warning);
  }
  commit(v, std::move(next), "pair loops");
  tool_ = Tool::Keys;  // where the user moves the key
}

void MergeApp::suggest_all_keys(viewer::Viewer& v) {
  if (setup().pairs.empty()) return v.flash("pair a source loop with a target loop first (tool 1)");
  MergeSetup next = setup();
  try {
    const std::vector<mesh_merge::KeySuggestion> s = mesh_merge::suggest_keys(next, source_.loops(), target_.loops());
    for (size_t p = 0; p < s.size(); ++p) flash_suggestion(v, static_cast<int>(p), s[p]);
  } catch (const Error& e) {
    return v.flash(e.what(), viewer::Tone::Error);
  }
  commit(v, std::move(next), "suggest keys");
}

std::string MergeApp::result_flag() const {
  if (!shown_) return {};
  char buf[256];
  if (shown_->detail.turn_deg > 90) {
    std::snprintf(buf, sizeof buf,
                  "FLIPPED: the merge turned the source %.0f deg from its placement (a key on the wrong side of the "
                  "loop?): K suggests keys as it is placed",
                  shown_->detail.turn_deg);
    return buf;
  }
  if (shown_->quality.folded_seam_edges > 0) {
    std::snprintf(buf, sizeof buf, "FOLDED: %d seam edges fold over %.0f deg (max %.0f deg)",
                  shown_->quality.folded_seam_edges, geometry::kFoldedDihedralDeg,
                  shown_->quality.seam_dihedral_max_deg);
    return buf;
  }
  return {};
}

void MergeApp::flash_suggestion(viewer::Viewer& v, int pair, const mesh_merge::KeySuggestion& s) {
  char buf[256];
  if (s.decisive()) {
    std::snprintf(buf, sizeof buf,
                  "pair %d: key suggested as the source is placed (K again after moving it, tool 2 sets your own)",
                  pair + 1);
    v.flash(buf);
  } else {
    std::snprintf(buf, sizeof buf,
                  "pair %d: key suggested, but the loops are nearly round (misfit %.2f, next best turn %.2f): check "
                  "which way round the result is",
                  pair + 1, s.residual, s.runner_up);
    v.flash(buf, viewer::Tone::Warning);
  }
}

// A merge shown in place of the inputs (after auto-merge, say) hides the source's loops: a click
// that picks on the inputs brings them back first, and picks on them at once.
void MergeApp::show_inputs_to_pick(viewer::Viewer& v) {
  if (!show_result_ || !shown_) return;
  show_result_ = false;
  update_scene(v);
  v.flash("the inputs are shown to pick on (Tab: the result)");
}

void MergeApp::click_keys(viewer::Viewer& v, double x, double y) {
  show_inputs_to_pick(v);
  std::vector<int> source_loops, target_loops;
  for (const auto& p : setup().pairs) source_loops.push_back(p.source_loop), target_loops.push_back(p.target_loop);
  if (source_loops.empty()) return v.flash("pair a source loop with a target loop first (tool 1)");
  // As loops: wherever the loop's line is drawn (on top), the source's while it is drawn.
  const auto cam = v.camera_matrices();
  const viewer::LoopPick s =
      v.scene().meshes["source"].visible
          ? viewer::pick_loop_vertex(cam, source_.mesh.V, source_.loops(), x, y, kPickPixels, {}, source_loops)
          : viewer::LoopPick{};
  const viewer::LoopPick t =
      viewer::pick_loop_vertex(cam, target_.mesh.V, target_.loops(), x, y, kPickPixels, {}, target_loops);
  if (!s && !t) return v.flash("no vertex of a paired loop there");
  if (s && (!t || s.pixels <= t.pixels))
    pending_key_source_ = s.vertex;
  else
    pending_key_target_ = t.vertex;
  if (pending_key_source_ < 0 || pending_key_target_ < 0) return;
  // Both ends picked: they must lie on the two loops of one pair.
  int pair = -1;
  for (size_t p = 0; p < setup().pairs.size(); ++p) {
    const auto& sl = source_.loops()[static_cast<size_t>(setup().pairs[p].source_loop)];
    const auto& tl = target_.loops()[static_cast<size_t>(setup().pairs[p].target_loop)];
    if (std::find(sl.begin(), sl.end(), pending_key_source_) != sl.end() &&
        std::find(tl.begin(), tl.end(), pending_key_target_) != tl.end())
      pair = static_cast<int>(p);
  }
  const int ks = pending_key_source_, kt = pending_key_target_;
  pending_key_source_ = pending_key_target_ = -1;
  if (pair < 0) return v.flash("the two key vertices lie on loops of different pairs");
  MergeSetup next = setup();
  try {
    mesh_merge::add_key(next, pair, {ks, kt},
                        source_.loops()[static_cast<size_t>(next.pairs[static_cast<size_t>(pair)].source_loop)]);
  } catch (const Error& e) {
    return v.flash(e.what(), viewer::Tone::Error);
  }
  commit(v, std::move(next), "key correspondence");
}

void MergeApp::click_handles(viewer::Viewer& v, double x, double y) {
  const auto hit = viewer::pick(*source_.bvh, v.camera_matrices(), x, y);
  if (!hit) return v.flash("fixed handles are source vertices: click on the source");
  const int vertex = viewer::nearest_corner(source_.mesh, *hit);
  if (source_.conn->is_boundary_vertex(vertex)) return v.flash("a fixed handle cannot lie on the merging boundary");
  MergeSetup next = setup();
  mesh_merge::toggle_handle(next, vertex);
  if (next.options.mode != mesh_merge::MergeMode::Dependent)
    v.flash("fixed handles act in configuration-dependent mode");
  commit(v, std::move(next), "fixed handle");
}

// ---------------------------------------------------------------- engine

bool MergeApp::auto_merge_allowed() const {
  if (!auto_merge_) return false;
  if (!mesh_merge::missing_input(setup(), static_cast<int>(source_.loops().size())).empty()) return false;
  return !remerge_ms_ || *remerge_ms_ < kAutoMergeMs;
}

namespace {

// The worker's job for the loop-pair modes: the Merger kept while the source and the options it
// was precomputed for stay, then the merge and its metrics.
template <class Slot>
void merge_loops(MergeOutcome& out, Slot& slot, const MergeSetup& s) {
  if (!slot.merger || slot.source != s.source || slot.placement != s.placement ||
      !same_options(slot.options, s.options)) {
    slot.merger.reset();  // free the old factorization before building the next
    slot.merger = std::make_unique<mesh_merge::Merger>(mesh_merge::placed_source(s), s.options);
    slot.source = s.source;
    slot.placement = s.placement;
    slot.options = s.options;
  } else {
    out.reused = true;
  }
  out.precompute_ms = slot.merger->precompute_ms();
  slot.merger->set_smoothing(s.options.smooth_iterations, s.options.smooth_rings, s.options.smooth_lambda);
  out.result = slot.merger->merge(*s.target, mesh_merge::loop_pairs(s));
  out.quality = mesh_merge::seam_quality(*s.target, out.result);
  out.detail = mesh_merge::detail_preservation(slot.merger->source(), out.result);
}

}  // namespace

void MergeApp::request_merge() {
  if (requested_revision_ == revision()) return;  // already on its way (or done)
  requested_revision_ = revision();
  auto slot = engine_;
  const MergeSetup s = setup();
  const std::uint64_t revision = this->revision();
  const bool optimal = optimal_mode();
  std::shared_ptr<const mesh_merge::BoundaryOptimizer> opt = optimal ? optimizer() : nullptr;
  const std::string opt_error = optimizer_.error;
  const mesh_merge::Placement2D placement = optimal ? current_placement() : mesh_merge::Placement2D{};
  auto progress = optimal_progress_;
  worker_.submit([slot, s, revision, optimal, opt, opt_error, placement, progress] {
    MergeOutcome out;
    out.revision = revision;
    out.source = s.source, out.target = s.target;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      if (optimal) {
        run_optimal(out, s, opt, opt_error, placement, progress);
      } else {
        merge_loops(out, *slot, s);
      }
    } catch (const Error& e) {
      out.error = e.what();
    } catch (const std::exception& e) {  // e.g. out of memory: reported, never a crash
      out.error = std::string("internal error: ") + e.what();
    }
    out.job_ms = ms_since(t0);
    return out;
  });
}

void MergeApp::receive_merge(viewer::Viewer& v) {
  std::optional<MergeOutcome> r = worker_.take();
  if (!r) return;
  job_ms_.push_back(r->job_ms);
  remerge_ms_ = remerge_ms(*r);
  frame_at_merge_ms_.push_back(v.last_frame_ms());
  if (!r->error.empty())
    v.flash("merge failed: " + r->error, viewer::Tone::Error);
  else if (r->source == setup().source && r->target == setup().target) {  // not one of meshes since replaced
    shown_ = *r, scene_dirty_ = true;
    if (const std::string flag = result_flag(); !flag.empty())
      std::fprintf(stderr, "lapis-merge: %s\n", flag.c_str());  // logs of batch runs
  }
  last_ = std::move(r);
}

void MergeApp::on_frame(viewer::Viewer& v) {
  receive_merge(v);
  if (revision() != requested_revision_ && auto_merge_allowed()) request_merge();
  if (export_pending_ && !worker_.busy()) {
    if (last_ && last_->revision == revision())
      export_all(v);
    else if (requested_revision_ != revision())
      request_merge();  // export what is on screen, up to date
  }
  if (scene_dirty_) update_scene(v);
  update_gizmo(v);
}

void MergeApp::on_exit(viewer::Viewer& v) {
  worker_.wait();
  worker_.set_on_done({});  // the window goes away after this
  receive_merge(v);
  if (paths_.export_on_exit) {
    if (!last_ || last_->revision != revision()) {
      request_merge();
      worker_.wait();
      receive_merge(v);
    }
    if (!export_all(v)) exit_status_ = 1;
  }
}

void MergeApp::benchmark_fields(nlohmann::json& j) const {
  j["app"] = "lapis-merge";
  j["source"] = source_name();
  j["target"] = target_name();
  j["source_vertices"] = setup().source ? setup().source->num_vertices() : 0;
  j["target_vertices"] = setup().target ? setup().target->num_vertices() : 0;
  j["merge_job_ms"] = job_ms_;
  j["frame_ms_when_merge_arrived"] = frame_at_merge_ms_;
  if (shown_) {
    const auto& t = shown_->result.timings;
    j["last_merge"] = {{"precompute_ms", shown_->precompute_ms},
                       {"precompute_reused", shown_->reused},
                       {"setup_ms", t.setup_ms},
                       {"solve_ms", t.solve_ms},
                       {"zip_ms", t.zip_ms},
                       {"smooth_ms", t.smooth_ms},
                       {"merge_ms", t.total_ms},
                       {"job_ms", shown_->job_ms},
                       {"seam_valid", shown_->quality.valid()},
                       {"merged_vertices", shown_->result.mesh.num_vertices()}};
  }
}

}  // namespace lapis::merge_app
