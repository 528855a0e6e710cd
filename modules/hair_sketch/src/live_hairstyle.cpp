#include "lapis/hair_sketch/live_hairstyle.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <string>
#include <utility>
#include <variant>

#include "lapis/core/error.h"
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

// The listed strands of `from`, in the order listed.
Strands pick_strands(const Strands& from, const std::vector<int>& indices) {
  Strands out;
  for (const int i : indices) {
    out.points.insert(out.points.end(), from.points.begin() + from.offsets[i],
                      from.points.begin() + from.offsets[i + 1]);
    out.offsets.push_back(static_cast<int>(out.points.size()));
  }
  return out;
}

// Copies `from` into `to`'s storage (a fresh allocation pays a page fault per 4 KB).
void copy_into(const Strands& from, Strands& to) {
  to.points.assign(from.points.begin(), from.points.end());
  to.offsets.assign(from.offsets.begin(), from.offsets.end());
}

}  // namespace

void LiveHairstyle::solve(const std::vector<StylePrimitive>& primitives, LiveUpdate& out) {
  solved_valid_ = grown_valid_ = false;  // until the solves below complete
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
  solved_primitives_ = primitives;
  solved_valid_ = true;
}

void LiveHairstyle::solve_if_changed(const std::vector<StylePrimitive>& primitives,
                                     const std::vector<StrandDetail>& details, const char* fn, LiveUpdate& out) {
  for (const auto& d : details) check_detail(d, head_->mesh.num_vertices(), fn);
  const auto t0 = std::chrono::steady_clock::now();
  if (!solved_valid_ || !same_primitives(primitives, solved_primitives_)) solve(primitives, out);
  out.solve_ms = ms_since(t0);
  out.constraints = (avoided_used_ ? avoided_->constraints() : field_.constraints()).size();
}

void LiveHairstyle::prepare_clearance(const std::vector<StrandDetail>& details) {
  if (!clearance_ && (settings_.growth.keep_outside_head || !details.empty())) {
    clearance_ = std::make_unique<HeadClearance>(*head_, field_.grid());
    detail_context_ = detail_context(*head_, roots_, clearance_.get(), settings_.growth.head_clearance);
  }
}

SampledField LiveHairstyle::sampled_field() const {
  return SampledField(field_.grid(), field(), settings_.growth.keep_outside_head ? clearance_.get() : nullptr);
}

LiveUpdate LiveHairstyle::update(const std::vector<StylePrimitive>& primitives,
                                 const std::vector<StrandDetail>& details, Strands reuse) {
  LiveUpdate out;
  out.strands = std::move(reuse);
  const auto t0 = std::chrono::steady_clock::now();
  solve_if_changed(primitives, details, "hair_sketch::LiveHairstyle::update()", out);
  out.regrown = !grown_valid_;
  const auto t1 = std::chrono::steady_clock::now();
  prepare_clearance(details);
  if (out.regrown) {
    grower_.set_options(settings_.growth);
    grower_.grow(sampled_field(), roots_, grown_);
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

LiveUpdate LiveHairstyle::preview(const std::vector<StylePrimitive>& primitives,
                                  const std::vector<StrandDetail>& details, int stride) {
  constexpr const char* fn = "hair_sketch::LiveHairstyle::preview()";
  if (stride < 1)
    throw InvalidArgument(std::string(fn) + ": the stride must be at least 1, got " + std::to_string(stride));
  LiveUpdate out;
  const auto t0 = std::chrono::steady_clock::now();
  solve_if_changed(primitives, details, fn, out);
  out.regrown = true;
  const auto t1 = std::chrono::steady_clock::now();
  prepare_clearance(details);
  // The strands shown, and the clumps' guides they follow: `grown` holds strand subset[k].
  std::vector<int> shown, subset;
  for (int i = 0; i < static_cast<int>(roots_.size()); i += stride) shown.push_back(i);
  const std::vector<int> guides = details.empty() ? std::vector<int>{} : detail_guides(details, detail_context_);
  std::set_union(shown.begin(), shown.end(), guides.begin(), guides.end(), std::back_inserter(subset));
  Strands grown;
  if (grown_valid_) {  // already grown in this field: the subset of those
    grown = pick_strands(grown_, subset);
  } else {
    std::vector<Eigen::Vector3d> roots;
    roots.reserve(subset.size());
    for (const int i : subset) roots.push_back(roots_[i]);
    preview_grower_.set_options(settings_.growth);
    preview_grower_.grow(sampled_field(), roots, grown);
  }
  out.growth_ms = ms_since(t1);
  const auto t2 = std::chrono::steady_clock::now();
  if (details.empty()) {
    out.strands = std::move(grown);  // no clumps, no guides: the subset is the shown strands
  } else {
    DetailContext context = detail_context_;
    context.strand_index = subset;
    std::vector<int> shown_at;  // where each shown strand is in the subset
    for (const int i : shown)
      shown_at.push_back(static_cast<int>(std::lower_bound(subset.begin(), subset.end(), i) - subset.begin()));
    out.strands = pick_strands(apply_strand_detail(grown, details, context), shown_at);
  }
  out.detail_ms = ms_since(t2);
  out.total_ms = ms_since(t0);
  return out;
}

}  // namespace lapis::hair_sketch
