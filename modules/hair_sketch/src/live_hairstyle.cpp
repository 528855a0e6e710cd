#include "lapis/hair_sketch/live_hairstyle.h"

#include <algorithm>
#include <chrono>
#include <utility>

#include "lapis/hair_sketch/scalp_avoidance.h"

namespace lapis::hair_sketch {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

LiveHairstyle::LiveHairstyle(const Head& head, const HairstyleSettings& settings)
    : head_(&head),
      settings_(settings),
      field_(head, hairstyle_grid(head, settings), settings.field_method, settings.field, settings.field_detail,
             settings.gravity_prior),
      roots_(sample_roots(head, settings.roots)) {
  if (settings.scalp_avoidance)
    avoided_ = std::make_unique<StyleField>(head, field_.grid(), settings.field_method, settings.field,
                                            settings.field_detail, settings.gravity_prior);
}

LiveUpdate LiveHairstyle::update(const std::vector<StylePrimitive>& primitives, Strands reuse) {
  return update(primitives, {}, std::move(reuse));
}

namespace {

bool same_primitives(const std::vector<StylePrimitive>& a, const std::vector<StylePrimitive>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), same_primitive);
}

// Copies `from` into `to`'s storage (a fresh allocation pays a page fault per 4 KB).
void copy_into(const Strands& from, Strands& to) {
  to.points.assign(from.points.begin(), from.points.end());
  to.offsets.assign(from.offsets.begin(), from.offsets.end());
}

}  // namespace

LiveUpdate LiveHairstyle::update(const std::vector<StylePrimitive>& primitives,
                                 const std::vector<StrandDetail>& details, Strands reuse) {
  for (const auto& d : details) check_detail(d, head_->mesh.num_vertices(), "hair_sketch::LiveHairstyle::update()");
  LiveUpdate out;
  out.strands = std::move(reuse);
  const auto t0 = std::chrono::steady_clock::now();
  out.regrown = !grown_valid_ || !same_primitives(primitives, last_primitives_);
  if (out.regrown) {
    out.solves.push_back(field_.update(primitives));
    // §4.6: the avoidance constraints depend on the style field, so they follow its solve.
    avoided_used_ = settings_.scalp_avoidance && !field_.constraints().empty();
    if (avoided_used_) {
      const auto t = std::chrono::steady_clock::now();
      if (!avoidance_) avoidance_ = std::make_unique<ScalpAvoidance>(field_.grid(), *head_);
      const std::vector<hair_field::Constraint> avoid = avoidance_->constraints(field_.field());
      out.avoidance_ms = ms_since(t);
      out.solves.push_back(avoided_->update(primitives, avoid));
    }
  }
  out.solve_ms = ms_since(t0);
  out.constraints = (avoided_used_ ? avoided_->constraints() : field_.constraints()).size();
  const auto t1 = std::chrono::steady_clock::now();
  const bool keep_outside = settings_.growth.keep_outside_head;
  if (!clearance_ && (keep_outside || !details.empty())) {
    clearance_ = std::make_unique<HeadClearance>(*head_, field_.grid());
    detail_context_ = detail_context(*head_, roots_, clearance_.get(), settings_.growth.head_clearance);
  }
  if (out.regrown) {
    grown_valid_ = false;  // until the growth below completes
    grower_.set_options(settings_.growth);
    grower_.grow(SampledField(field_.grid(), field(), keep_outside ? clearance_.get() : nullptr), roots_, grown_);
    last_primitives_ = primitives;
    grown_valid_ = true;
  }
  out.growth_ms = ms_since(t1);
  const auto t2 = std::chrono::steady_clock::now();
  if (details.empty()) {
    copy_into(grown_, out.strands);
  } else {
    out.strands = apply_strand_detail(grown_, details, detail_context_);
  }
  out.detail_ms = ms_since(t2);
  out.total_ms = ms_since(t0);
  return out;
}

}  // namespace lapis::hair_sketch
