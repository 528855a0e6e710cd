// Strand detail on the bundled detail sessions: what a detail edit costs in the interactive
// loop (the details reapplied to strands already grown), what the one-time head clearance
// costs, and each detail kind alone, on 1 and 2 threads. The baseline in the same run is the
// regrowth the edit no longer needs.
//   bench_strand_detail [--roots 5000,20000] [--repetitions R]
#include <omp.h>

#include <cstring>
#include <filesystem>

#include "lapis/hair_sketch/live_hairstyle.h"
#include "lapis/hair_sketch/session.h"
#include "lapis/hair_sketch/strand_detail.h"
#include "lapis_bench.h"

using namespace lapis;
using namespace lapis::hair_sketch;

namespace {

std::vector<int> parse_list(const char* s) {
  std::vector<int> out;
  for (const char* p = s; *p;) {
    out.push_back(std::atoi(p));
    while (*p && *p != ',') ++p;
    if (*p == ',') ++p;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  bench::check_options(argc, argv, {"--roots", "--repetitions"},
                       "usage: bench_strand_detail [--roots 5000,20000] [--repetitions R]\n");
  std::vector<int> root_counts{5000, 20000};
  int repetitions = 5;
  for (int i = 1; i + 1 < argc; ++i) {
    if (!std::strcmp(argv[i], "--roots")) root_counts = parse_list(argv[++i]);
    if (!std::strcmp(argv[i], "--repetitions")) repetitions = std::max(1, std::atoi(argv[++i]));
  }
  const std::filesystem::path dir = std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "sessions";
  bench::Table table({"session", "strands", "threads", "what", "segments out", "ms (median)"});
  nlohmann::json out;
  out["rows"] = nlohmann::json::array();
  const auto record = [&](const std::string& session, int strands, int threads, const std::string& what, int segments,
                          const std::vector<double>& ms) {
    table.row({session, std::to_string(strands), std::to_string(threads), what, std::to_string(segments),
               bench::fmt(bench::median(ms))});
    out["rows"].push_back({{"session", session},
                           {"strands", strands},
                           {"threads", threads},
                           {"what", what},
                           {"segments", segments},
                           {"ms", ms},
                           {"median_ms", bench::median(ms)}});
  };
  for (const char* name : {"curly_bob", "wavy_long"}) {
    Hairstyle style = load_session(dir / (std::string(name) + ".json"));
    const Head head = load_session_head(style, dir / (std::string(name) + ".json"));
    for (const int roots : root_counts) {
      style.settings.roots.count = roots;
      LiveHairstyle live(head, style.settings);
      LiveUpdate grown = live.update(style.primitives);
      const int strands = grown.strands.count();
      std::vector<double> clearance_ms;
      for (int r = 0; r < 2; ++r)
        clearance_ms.push_back(bench::time_ms([&] { const HeadClearance c(head, live.grid()); }));
      record(name, strands, omp_get_max_threads(), "head clearance (once)", 0, clearance_ms);
      const HeadClearance clearance(head, live.grid());
      const DetailContext context = detail_context(head, live.roots(), &clearance);
      for (const int threads : {1, 2}) {
        omp_set_num_threads(threads);
        for (const auto& d : style.details) {
          std::vector<double> ms;
          int segments = 0;
          for (int r = 0; r < repetitions; ++r)
            ms.push_back(
                bench::time_ms([&] { segments = apply_strand_detail(grown.strands, {d}, context).segments(); }));
          record(name, strands, threads, std::string("only ") + detail_type(d), segments, ms);
        }
      }
      // The interactive edit: every detail reapplied (live), against the regrowth it replaces.
      live.update(style.primitives, style.details);  // the clearance is built here
      std::vector<double> edit, regrow;
      int segments = 0;
      for (int r = 0; r < repetitions; ++r) {
        style.details.front().seed += 1;  // a detail edit
        edit.push_back(
            bench::time_ms([&] { segments = live.update(style.primitives, style.details).strands.segments(); }));
        LiveHairstyle baseline(head, style.settings);  // set-up not timed
        regrow.push_back(bench::time_ms([&] { baseline.update(style.primitives); }));
      }
      record(name, strands, omp_get_max_threads(), "detail edit (all details, live)", segments, edit);
      record(name, strands, omp_get_max_threads(), "baseline: solve + regrowth", grown.strands.segments(), regrow);
    }
  }
  table.print();
  out["peak_rss_mib"] = bench::peak_rss_mib();
  bench::write_results("strand_detail", out);
  return 0;
}
