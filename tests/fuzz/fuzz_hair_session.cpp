// Fuzz target: a hairstyle session as `lapis hair` runs it — parsed, its strokes replayed,
// the field solved and the strands grown on the bundled head. The session's own paths are
// ignored (the fuzzer must not open files it names) and the work is bounded: small parser
// limits, a memory limit on the grid and solver, and sessions asking for more grid, roots,
// strand length, curve length or constraint samples than below are skipped, so one input takes well
// under a second.
#include <variant>

#include "fuzz_input.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/stroke_commands.h"
#include "lapis/hair_sketch/style_field.h"

#ifndef LAPIS_SOURCE_DIR
#error "LAPIS_SOURCE_DIR must name the source tree (for assets/head.obj)"
#endif

namespace {

using namespace lapis::hair_sketch;

constexpr double kMaxUnknowns = 1000;  // the seeds' grids; 2000 took 1.2 s under ASan + coverage
constexpr int kMaxRoots = 32;
constexpr double kMaxSegmentsPerStrand = 200;
constexpr int kMaxSamples = 16;  // dividing curves' samples_per_side, tail segments
// Curve length in grid spacings, over all primitives. The library takes up to 2^20 samples a
// curve (0.1 s in release, 3 s under ASan + coverage for a replayed stroke that long).
constexpr double kMaxCurveSpacings = 4096;
constexpr double kMemoryLimitBytes = 256.0 * (1 << 20);

const Head& bundled_head() {
  static const Head head = load_bundled_head(LAPIS_SOURCE_DIR);
  return head;
}

double polyline_length(const std::vector<Eigen::Vector3d>& p) {
  double length = 0;
  for (size_t i = 1; i < p.size(); ++i) length += (p[i] - p[i - 1]).norm();
  return length;
}

double curve_spacings(const Hairstyle& s, const Head& head) {
  double length = 0;
  for (const auto& p : s.primitives) {
    if (const auto* c = std::get_if<StreamCurve>(&p.shape)) length += polyline_length(c->points);
    if (const auto* d = std::get_if<DividingCurve>(&p.shape)) length += polyline_length(d->points);
    if (const auto* t = std::get_if<Ponytail>(&p.shape))
      for (const auto* line : {&t->spine, &t->cross_section, &t->profile_a, &t->profile_b})
        length += polyline_length(*line);
  }
  return length / hairstyle_grid(head, s.settings).spacing;
}

bool affordable(const Hairstyle& s, const Head& head) {
  const auto& set = s.settings;
  if (!(set.grid.target_unknowns <= kMaxUnknowns) || set.roots.count > kMaxRoots) return false;
  if (!(set.growth.max_length <= kMaxSegmentsPerStrand * set.growth.step)) return false;
  if (set.sketch.tail_segments > kMaxSamples) return false;
  for (const auto& p : s.primitives) {
    if (const auto* d = std::get_if<DividingCurve>(&p.shape); d && d->samples_per_side > kMaxSamples) return false;
    if (const auto* c = std::get_if<StreamCurve>(&p.shape); c && c->tail_segments > kMaxSamples) return false;
  }
  return curve_spacings(s, head) <= kMaxCurveSpacings;
}

}  // namespace

// The head is loaded once before the first input: its 2 s under ASan are not an input's time
// (libFuzzer's -timeout=1 counted them against whichever input came first).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  bundled_head();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const Head& head = bundled_head();
  return lapis::fuzz::expect_lapis_errors_only([&] {
    SessionLimits limits;
    limits.max_file_bytes = 1 << 20;
    limits.max_points = 256;
    limits.max_items = 16;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    Hairstyle session = session_from_json(text, "<fuzz>", limits);
    if (!affordable(session, head)) throw lapis::ResourceLimit("fuzz_hair_session: settings beyond the fuzzing limits");
    session.settings.grid.memory_limit_bytes = kMemoryLimitBytes;
    session.settings.field.memory_limit_bytes = kMemoryLimitBytes;
    const Hairstyle style = session.strokes.empty() ? session : replay_strokes(session, head);
    if (!affordable(style, head))
      throw lapis::ResourceLimit("fuzz_hair_session: replayed primitives beyond the fuzzing limits");
    (void)build_hairstyle(style, head);
  });
}
