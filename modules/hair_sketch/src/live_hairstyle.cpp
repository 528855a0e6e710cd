#include "lapis/hair_sketch/live_hairstyle.h"

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
      field_(head, hairstyle_grid(head, settings), settings.field_method, settings.field),
      roots_(sample_roots(head, settings.roots)) {}

LiveUpdate LiveHairstyle::update(const std::vector<StylePrimitive>& primitives, Strands reuse) {
  LiveUpdate out;
  out.strands = std::move(reuse);
  const auto t0 = std::chrono::steady_clock::now();
  out.solves.push_back(field_.update(primitives));
  // §4.6: the avoidance constraints depend on the style field, so they follow its solve.
  if (settings_.scalp_avoidance && !primitives.empty())
    out.solves.push_back(field_.update(primitives, scalp_avoidance_constraints(field_.grid(), field_.field(), *head_)));
  out.solve_ms = ms_since(t0);
  out.constraints = field_.constraints().size();
  const auto t1 = std::chrono::steady_clock::now();
  grower_.set_options(settings_.growth);
  grower_.grow(SampledField(field_.grid(), field_.field()), roots_, out.strands);
  out.growth_ms = ms_since(t1);
  out.total_ms = ms_since(t0);
  return out;
}

}  // namespace lapis::hair_sketch
