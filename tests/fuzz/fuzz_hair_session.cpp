// Fuzz target: a hairstyle session as `lapis hair` runs it — parsed, its strokes replayed,
// the field solved and the strands grown on the bundled head. The session's own paths are
// ignored (the fuzzer must not open files it names) and the work is bounded: small parser
// limits, a memory limit on the grid and solver, and sessions asking for more grid, roots,
// strand length or constraint samples than below are skipped, so one input takes well
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

constexpr double kMaxUnknowns = 2000;
constexpr int kMaxRoots = 32;
constexpr double kMaxSegmentsPerStrand = 200;
constexpr int kMaxSamples = 16;  // dividing curves' samples_per_side, tail segments
constexpr double kMemoryLimitBytes = 256.0 * (1 << 20);

const Head& bundled_head() {
  static const Head head = load_bundled_head(LAPIS_SOURCE_DIR);
  return head;
}

bool affordable(const Hairstyle& s) {
  const auto& set = s.settings;
  if (!(set.grid.target_unknowns <= kMaxUnknowns) || set.roots.count > kMaxRoots) return false;
  if (!(set.growth.max_length <= kMaxSegmentsPerStrand * set.growth.step)) return false;
  if (set.sketch.tail_segments > kMaxSamples) return false;
  for (const auto& p : s.primitives) {
    if (const auto* d = std::get_if<DividingCurve>(&p.shape); d && d->samples_per_side > kMaxSamples) return false;
    if (const auto* c = std::get_if<StreamCurve>(&p.shape); c && c->tail_segments > kMaxSamples) return false;
  }
  return true;
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
    if (!affordable(session)) throw lapis::ResourceLimit("fuzz_hair_session: settings beyond the fuzzing limits");
    session.settings.grid.memory_limit_bytes = kMemoryLimitBytes;
    session.settings.field.memory_limit_bytes = kMemoryLimitBytes;
    const Hairstyle style = session.strokes.empty() ? session : replay_strokes(session, head);
    if (!affordable(style))
      throw lapis::ResourceLimit("fuzz_hair_session: replayed primitives beyond the fuzzing limits");
    (void)build_hairstyle(style, head);
  });
}
