#include "lapis/mesh_deform/live_deformer.h"

#include <chrono>
#include <cstdio>

#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/salient_deformer.h"

namespace lapis::mesh_deform {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

std::string timing_of(const Deformer& d) {
  char buf[160] = "";
  if (const auto* i = dynamic_cast<const ImplicitLaplacianDeformer*>(&d)) {
    const ImplicitReport& s = i->report();
    std::snprintf(buf, sizeof buf, "Eq. 2.8 %.0f ms, polar %.0f ms, Eq. 2.10 %.0f ms%s", s.first_solve_ms, s.polar_ms,
                  s.second_solve_ms, s.guided ? ", guided" : "");
  } else if (const auto* a = dynamic_cast<const ArapDeformer*>(&d)) {
    const ArapReport& s = a->report();
    std::snprintf(buf, sizeof buf, "%d iterations: local %.0f ms, global %.0f ms", s.iterations, s.rotations_ms,
                  s.solves_ms);
  } else if (const auto* sd = dynamic_cast<const SalientDeformer*>(&d)) {
    const SalientReport& s = sd->report();
    std::snprintf(buf, sizeof buf, "%d iterations: fits %.0f ms, solves %.1f ms, %d features, %d subspace vertices",
                  s.iterations, s.rotations_ms, s.solves_ms, s.features, s.subspace_vertices);
  } else if (const auto* e = dynamic_cast<const EdgeLaplacianDeformer*>(&d)) {
    const EdgeLaplacianReport& s = e->report();
    std::snprintf(buf, sizeof buf, "%d iterations: fits %.0f ms, solves %.0f ms, last move %.2g", s.iterations,
                  s.fit_ms, s.solve_ms, s.last_move);
  } else if (const auto* iso = dynamic_cast<const IsolinesDeformer*>(&d)) {
    const IsolinesReport& s = iso->report();
    std::snprintf(buf, sizeof buf, "%d iterations %.1f ms (%d triangles), reconstruction %.0f ms", s.iterations,
                  s.iterate_ms, s.sampled_triangles, s.reconstruct_ms);
  }
  return buf;
}

}  // namespace

LiveDeformer::LiveDeformer(TriMesh rest) : rest_(std::move(rest)) {}
LiveDeformer::~LiveDeformer() = default;

// The cached detection (run now if the options changed) and the user's features.
void LiveDeformer::prepare_salient(SalientDeformer& d, const LiveRequest& r) {
  const SalientOptions& o = r.settings.salient;
  if (o.detect_features) {
    if (!detection_ || !(detection_options_ == o.detection)) {
      detection_ = detect_salient_features(rest_, o.detection);
      detection_options_ = o.detection;
    }
    d.set_detection(*detection_);
  }
  if (!r.features.empty()) d.set_features(r.features);
}

LiveFrame LiveDeformer::update(const LiveRequest& r) {
  LiveFrame f;
  if (!deformer_ || !(r.settings == settings_) || r.selection_revision != selection_revision_ ||
      r.features_revision != features_revision_ || deformer_->dirty()) {
    deformer_.reset();  // free the old factorizations before building the new ones
    history_.clear();
    auto d = make_deformer(rest_, r.settings);
    if (auto* s = dynamic_cast<SalientDeformer*>(d.get())) prepare_salient(*s, r);
    d->set_selection(r.selection);
    const auto t0 = std::chrono::steady_clock::now();
    d->precompute();  // throws for an invalid selection; deformer_ stays empty, so we retry
    setup_ms_ = ms_since(t0);
    deformer_ = std::move(d);
    settings_ = r.settings;
    selection_revision_ = r.selection_revision;
    features_revision_ = r.features_revision;
    f.did_setup = true;
  }
  auto* implicit = dynamic_cast<ImplicitLaplacianDeformer*>(deformer_.get());
  if (implicit) {
    implicit->set_preview(r.preview);
    f.preview = r.preview;
    f.degenerate_vertices = implicit->degenerate_vertices();
  }
  if (auto* iso = dynamic_cast<IsolinesDeformer*>(deformer_.get())) {
    iso->set_preview_stride(r.preview ? kIsolinePreviewStride : 0);
    f.preview = r.preview;
    if (f.did_setup) {
      f.isoline_field = iso->fields().col(iso->isoline_sets() == 1 ? 1 : 0);
      f.rigidity = iso->rigidity();
      f.isolines = iso->isolines_of_set(0);
    }
  }
  auto t0 = std::chrono::steady_clock::now();
  f.positions = deformer_->deform(r.transforms);
  f.solve_ms = ms_since(t0);
  history_.push_back(r.transforms);
  f.history = history_;
  f.setup_ms = setup_ms_;
  f.method = deformer_->name();
  f.timing = timing_of(*deformer_);
  if (const auto* a = dynamic_cast<const ArapDeformer*>(deformer_.get())) f.energy = a->report().energy;
  if (const auto* s = dynamic_cast<const SalientDeformer*>(deformer_.get())) {
    f.saliency = s->saliency();
    f.features = s->features();
  }
  if (r.field) {
    t0 = std::chrono::steady_clock::now();
    f.distortion = vertex_distortion(rest_, f.positions, *r.field);
    f.distortion_ms = ms_since(t0);
  }
  return f;
}

}  // namespace lapis::mesh_deform
