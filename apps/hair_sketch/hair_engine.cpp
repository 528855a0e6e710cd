// The hair app's engine side: regrowth on the worker (a preview of the strands on screen
// first, then the rest), what each edit cost by stage (--benchmark).
#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "hair_sketch_app.h"
#include "lapis/hair_sketch/style_field.h"
#include "strand_display.h"

namespace lapis::hair_app {
namespace {

// How long an edit's curves wait for its strands (scene_held_since_): about twice a regrowth
// at the default grid.
constexpr double kSceneHoldSeconds = 0.4;

}  // namespace
void HairSketchApp::settings_changed() {
  ++settings_epoch_;
  grid_ = hairstyle_grid(head_, document_.style().settings);
  request_regrowth();
}

void FrameGate::open() {
  {
    std::lock_guard lock(mutex_);
    open_ = true;
  }
  opened_.notify_all();
}

void FrameGate::wait() {
  std::unique_lock lock(mutex_);
  opened_.wait_for(lock, std::chrono::seconds(1), [this] { return open_; });
}

// The window draws every k-th strand (display_stride): a regrowth shows those first, grown
// alone, then grows the rest. Not for the first strands (no stride known yet), a window that
// draws every strand, or other settings (other roots).
int HairSketchApp::preview_stride() const {
  const int budget = static_cast<int>(strand_budget_.value());
  if (!last_ || budget == 0 || last_->settings_epoch != settings_epoch_) return 0;
  const int k = display_stride(last_->update.strands, {.max_segments = budget, .current_stride = shown_stride_});
  return k > 1 ? k : 0;
}

void HairSketchApp::request_regrowth() {
  if (requested_revision_ == document_.revision() && requested_epoch_ == settings_epoch_) return;
  requested_revision_ = document_.revision();
  requested_epoch_ = settings_epoch_;
  auto slot = engine_;
  const Head* head = &head_;
  const HairstyleSettings settings = document_.style().settings;
  const std::vector<StylePrimitive> primitives = document_.style().primitives;
  const std::vector<StrandDetail> details = document_.style().details;
  const std::uint64_t revision = document_.revision(), epoch = settings_epoch_;
  const int stride = preview_stride();
  if (preview_gate_) preview_gate_->open();  // an older job's: nothing holds the new one back
  preview_gate_ = stride > 0 ? std::make_shared<FrameGate>() : nullptr;
  // The strands last replaced on screen go with the job, to be written over (their
  // storage is already paged in: LiveHairstyle::update).
  const auto submitted = std::chrono::steady_clock::now();
  worker_.submit([slot, head, settings, primitives, details, revision, epoch, submitted, stride, gate = preview_gate_,
                  worker = &worker_, spare = std::move(spare_strands_)]() mutable {
    const auto start = std::chrono::steady_clock::now();
    if (!slot->live || slot->epoch != epoch) {
      slot->live.reset();  // free the old solver before building the new one
      slot->live = std::make_unique<LiveHairstyle>(*head, settings);
      slot->epoch = epoch;
    }
    const auto finish = [&](Regrowth& r) {
      r.revision = revision;
      r.settings_epoch = epoch;
      r.grid = slot->live->grid();
      r.field = std::make_shared<const Field>(slot->live->field());
      r.finished = std::chrono::steady_clock::now();
      r.worker_ms = std::chrono::duration<double, std::milli>(r.finished - start).count();
      r.queued_ms = std::chrono::duration<double, std::milli>(start - submitted).count();
    };
    if (stride > 0) {
      Regrowth preview;
      preview.preview_stride = stride;
      preview.update = slot->live->preview(primitives, details, stride);
      finish(preview);
      worker->post(std::move(preview));
      gate->wait();
      if (worker->superseded()) {
        Regrowth stopped;
        stopped.superseded = true;
        stopped.update.strands = std::move(spare);
        return stopped;
      }
    }
    Regrowth r;
    r.update = slot->live->update(primitives, details, std::move(spare));
    finish(r);
    return r;
  });
}

void HairSketchApp::receive_preview(viewer::Viewer& v, Regrowth r) {
  const double display_start = v.time();
  shown_preview_ = ShownPreview{r.revision, r.settings_epoch, std::move(r.update.strands), r.preview_stride};
  update_strand_item(v, shown_preview_->strands, shown_preview_->stride);
  preview_drawn_in_frame_ = v.frame();
  if (scene_held_since_ >= 0) end_scene_hold(v);  // the edit's curves with its strands, in one frame
  if (r.revision == document_.revision() && last_edit_time_ > 0) {
    edits_.push_back(stages(r, display_start, v.time()));
    edits_.back().preview = true;
    edit_drawn_in_frame_ = v.frame();
  }
}

void HairSketchApp::redraw_strands(viewer::Viewer& v) {
  if (shown_preview_)
    update_strand_item(v, shown_preview_->strands, shown_preview_->stride);
  else if (last_)
    update_strand_item(v, last_->update.strands);
}

void HairSketchApp::receive_regrowth(viewer::Viewer& v) {
  std::optional<Regrowth> r;
  try {
    r = worker_.take();
  } catch (const Error& e) {
    engine_error_ = e.what();
    v.flash(std::string("field update failed: ") + e.what(), viewer::Tone::Error);
    return;
  }
  if (!r) return;
  engine_error_.clear();
  if (r->preview_stride > 0) return receive_preview(v, std::move(*r));
  if (r->superseded) {  // the preview stays on screen until the newer edit's strands replace it
    spare_strands_ = std::move(r->update.strands);
    return;
  }
  const double display_start = v.time();
  // After its preview, the whole set shows the same strands unless the stride moved on.
  const bool previewed =
      shown_preview_ && shown_preview_->revision == r->revision && shown_preview_->settings_epoch == r->settings_epoch;
  const bool same_picture =
      previewed && display_stride(r->update.strands, {.max_segments = static_cast<int>(strand_budget_.value()),
                                                      .current_stride = shown_stride_}) == shown_stride_;
  if (!same_picture) update_strand_item(v, r->update.strands);
  shown_preview_.reset();
  if (r->revision == document_.revision() && last_edit_time_ > 0) {
    if (previewed && !edits_.empty() && edits_.back().preview && edits_.back().all_strands_ms == 0) {
      EditStages& e = edits_.back();
      e.rest_ms = r->update.growth_ms + r->update.detail_ms;
      e.all_strands_ms = (v.time() - last_edit_time_) * 1000.0;
      e.redrawn = !same_picture;
    } else {
      edits_.push_back(stages(*r, display_start, v.time()));
      edits_.back().all_strands_ms = edits_.back().total_ms - edits_.back().display_ms;
      edit_drawn_in_frame_ = v.frame();  // the frame's drawing is added once it is known
    }
  }
  if (last_) spare_strands_ = std::move(last_->update.strands);
  last_ = std::move(r);
  if (show_glyphs_) update_glyph_item(v);
}

void HairSketchApp::on_frame_shown(viewer::Viewer& v) {
  if (preview_gate_ && preview_drawn_in_frame_ >= 0 && v.frame() >= preview_drawn_in_frame_) {
    preview_gate_->open();
    preview_drawn_in_frame_ = -1;
  }
}

void HairSketchApp::on_frame(viewer::Viewer& v) {
  if (edit_drawn_in_frame_ >= 0 && v.frame() > edit_drawn_in_frame_) {
    // The frame that took the strands drew them after on_frame: its time less what on_frame
    // spent preparing them.
    EditStages& e = edits_.back();
    e.draw_ms = std::max(0.0, v.last_frame_ms() - e.display_ms);
    e.total_ms += e.draw_ms;
    edit_drawn_in_frame_ = -1;
  }
  // The previous frame's time adapts how much of the hair is drawn; not while the worker
  // regrows, whose share of the cores slows every frame whatever is drawn, and not after a frame
  // that reused the unchanged scene's picture, whose time says nothing about the strands.
  if (last_ && v.frame() > 0 && !busy() && v.last_frame_drew_scene() &&
      strand_budget_.observe(v.last_frame_ms(), last_->update.strands.segments()))
    update_strand_item(v, last_->update.strands);
  receive_regrowth(v);
  request_regrowth();  // no-op unless the document or settings moved on
  // A slow regrowth (a big grid) does not hide the edit's curves for long.
  if (scene_held_since_ >= 0 && (!busy() || v.time() - scene_held_since_ > kSceneHoldSeconds)) end_scene_hold(v);
  if (scene_held_since_ < 0) {
    if (head_dirty_) update_head_item(v);
    if (curves_dirty_) update_curve_items(v);
  }
  autosave_if_due(v);
}

EditStages HairSketchApp::stages(const Regrowth& r, double display_start, double now) const {
  EditStages e;
  e.total_ms = (now - last_edit_time_) * 1000.0;
  const LiveUpdate& u = r.update;
  if (!u.solves.empty()) e.style_solve_ms = u.solves.front().total_ms;
  e.avoidance_ms = u.avoidance_ms;
  if (u.solves.size() > 1) e.avoidance_solve_ms = u.solves[1].total_ms;
  for (const auto& s : u.solves) {
    e.iterations += s.iterations;
    e.solves.push_back(s.detail + ": update " + std::to_string(s.update_ms) + " ms, solve " +
                       std::to_string(s.solve_ms) + " ms");
  }
  e.growth_ms = u.growth_ms, e.detail_ms = u.detail_ms, e.occlusion_ms = occlusion_ms_;
  e.display_ms = (now - display_start) * 1000.0;
  e.waiting_ms = e.total_ms - r.worker_ms - e.display_ms;
  e.queued_ms = r.queued_ms;
  e.handover_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r.finished).count() - e.display_ms;
  return e;
}

void HairSketchApp::benchmark_fields(nlohmann::json& j) const {
  j["app"] = "lapis-hair-sketch";
  std::vector<double> totals;
  for (const auto& e : edits_) {
    totals.push_back(e.total_ms);
    j["edits"].push_back({{"total_ms", e.total_ms},
                          {"style_solve_ms", e.style_solve_ms},
                          {"avoidance_ms", e.avoidance_ms},
                          {"avoidance_solve_ms", e.avoidance_solve_ms},
                          {"iterations", e.iterations},
                          {"growth_ms", e.growth_ms},
                          {"detail_ms", e.detail_ms},
                          {"occlusion_ms", e.occlusion_ms},
                          {"display_ms", e.display_ms},
                          {"draw_ms", e.draw_ms},
                          {"waiting_ms", e.waiting_ms},
                          {"queued_ms", e.queued_ms},
                          {"handover_ms", e.handover_ms},
                          {"preview", e.preview},
                          {"rest_ms", e.rest_ms},
                          {"all_strands_ms", e.all_strands_ms},
                          {"redrawn", e.redrawn},
                          {"solves", e.solves}});
  }
  j["edit_to_strands_ms"] = totals;
  if (last_) {
    j["strands"] = last_->update.strands.count();
    j["segments"] = last_->update.strands.segments();
    j["grid_unknowns"] = last_->grid.num_nodes();
    j["last_solve_ms"] = last_->update.solve_ms;
    j["last_growth_ms"] = last_->update.growth_ms;
    j["last_total_ms"] = last_->update.total_ms;
    if (!last_->update.solves.empty()) j["field_method"] = to_string(last_->update.solves.front().method);
  }
  j["primitives"] = document_.style().primitives.size();
  j["drawn_segments"] = strand_budget_.value();  // 0: all
  j["drawn_strands"] = shown_strands_;
}

}  // namespace lapis::hair_app
