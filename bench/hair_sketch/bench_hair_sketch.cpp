// The interactive loop of hair sketching, per edit, on the bundled head: constraint diff,
// field update, regrowth, for a new stream curve of ~30 segments (a stroke) and for editing
// it (old constraints removed, new ones added), by the multigrid fast path, the thesis'
// update/downdate path and refactorization, in the same run.
//   bench_hair_sketch [--sizes 50000,250000,1000000] [--thesis-max N] [--repetitions R]
// Each method makes the stroke and the edit R times (3), the methods taking turns; the table
// shows each method's median repetition and the ratios to the multigrid path per repetition.
// Paths whose factor would not fit in memory are skipped (and said so).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/hair_field/field_solver.h"
#include "lapis/hair_sketch/growth.h"
#include "lapis/hair_sketch/head.h"
#include "lapis/hair_sketch/stream_curve.h"
#include "lapis_bench.h"
#include "memory_bandwidth.h"

using namespace lapis::hair_sketch;
using namespace lapis::hair_field;
namespace bench = lapis::bench;

namespace {

// A stroke over the head at 1.2 head radii from the centre: from near the crown at
// azimuth phi over the side of the head down to the ear line, then straight down; `bend`
// turns its azimuth along the way. `segments` grid spacings long.
StreamCurve curve_at(const Head& head, const Grid& g, double phi, int segments, double bend) {
  StreamCurve c;
  const double R = 1.2 * 0.5 * head.box.sizes().x();
  const double len = segments * g.spacing, arc = std::min(len, 1.3 * R);
  const int n = 40;
  for (int i = 0; i <= n; ++i) {
    const double a = 0.3 + (arc / R) * i / n;  // polar angle from the top
    const double p = phi + bend * i / n;
    c.points.push_back(head.center +
                       R * Eigen::Vector3d(std::sin(a) * std::cos(p), std::cos(a), std::sin(a) * std::sin(p)));
  }
  if (len > arc) c.points.push_back(c.points.back() - Eigen::Vector3d(0, len - arc, 0));
  return c;
}

// One edit: the solver's report and the stages around it.
struct Stage {
  FieldSolveReport field;
  double diff_ms = 0, grow_ms = 0, total_ms = 0;
};

std::vector<int> parse_list(const char* s) {
  std::vector<int> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(std::stoi(item));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(
      argc, argv, {"--sizes", "--thesis-max", "--repetitions"},
      "usage: bench_hair_sketch [--sizes 50000,250000,1000000] [--thesis-max N] [--repetitions R]\n"
      "  a stroke and its edit on the bundled head per field method; writes bench/results/hair_sketch.json\n");
  std::vector<int> sizes{50000, 250000, 1000000};
  int thesis_max = 60000;  // the thesis path at 250K costs minutes per run (30 s factorization)
  int repetitions = 3;     // of each edit per method, interleaved; the median is reported
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--sizes"))
      sizes = parse_list(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--thesis-max"))
      thesis_max = std::stoi(argv[i + 1]);
    else if (!std::strcmp(argv[i], "--repetitions"))
      repetitions = std::max(1, std::stoi(argv[i + 1]));
  }
  const Head head = load_bundled_head(LAPIS_SOURCE_DIR);
  const std::vector<int> strand_counts{10000, 20000, 100000};
  std::vector<std::vector<Eigen::Vector3d>> roots;
  for (int c : strand_counts) {
    RootOptions ro;
    ro.count = c;
    roots.push_back(sample_roots(head, ro));
  }
  nlohmann::json out;
  out["threads"] = omp_get_max_threads();
  out["repetitions"] = repetitions;
  const bench::MemoryBandwidth bandwidth = bench::measure_memory_bandwidth();
  out["memory_bandwidth"] = bandwidth.to_json();
  std::printf("memory read bandwidth: %.1f GB/s on one thread, %.1f GB/s on %d\n\n", bandwidth.one_thread_gbs,
              bandwidth.all_threads_gbs, bandwidth.threads);
  bench::Table table({"unknowns", "method", "edit", "nodes +/-", "diff ms", "update ms", "solve ms", "iters",
                      "grow20K ms", "total20K ms", "detail"});
  bench::Table growth({"unknowns", "strands", "segments", "grow ms", "fresh alloc ms"});
  std::vector<std::string> ratio_lines;
  for (int n : sizes) {
    GridOptions go;
    go.target_unknowns = n;
    const Grid g = make_grid(head.box, go);
    // The style the stroke lands in: six stream curves around the head.
    std::vector<std::vector<Constraint>> base;
    for (int k = 0; k < 6; ++k) base.push_back(curve_at(head, g, 2 * M_PI * k / 6 + 0.3, 60, 0.2).constraints(g));
    const ConstraintSet base_set = ConstraintSet::merge(base);
    const StreamCurve stroke = curve_at(head, g, -M_PI / 2 - 0.25, 30, 0.0);
    const StreamCurve edited = curve_at(head, g, -M_PI / 2 - 0.25, 30, 0.35);
    // The methods' solvers live side by side and take turns, repetition by repetition
    // (stroke, edit, back to the base style untimed), so a slow spell of this shared machine
    // falls on all of them; the rows report each method's median repetition.
    struct MethodRun {
      FieldMethod method;
      std::unique_ptr<FieldSolver> solver;
      StrandGrower grower;
      Strands strands;
      ConstraintSet current;
      double setup_ms = 0;
      std::vector<Stage> runs[2];  // stroke, edit
    };
    std::vector<MethodRun> methods;
    methods.reserve(3);
    std::vector<std::vector<std::string>> skipped;  // table rows, after the methods' rows
    for (FieldMethod m : {FieldMethod::Multigrid, FieldMethod::Thesis, FieldMethod::Refactorize}) {
      if (m != FieldMethod::Multigrid && n > thesis_max) {
        skipped.push_back({std::to_string(g.num_nodes()), to_string(m), "-", "", "", "", "", "", "", "",
                           "skipped: factor ~" + bench::fmt(estimate_cholesky_bytes(g.num_nodes()) / (1 << 30), 1) +
                               " GiB (--thesis-max)"});
        continue;
      }
      MethodRun& mr = methods.emplace_back();
      mr.method = m;
      mr.setup_ms = bench::time_ms([&] { mr.solver = make_field_solver(g, m); });
      mr.setup_ms += bench::time_ms([&] { mr.solver->apply(diff(ConstraintSet(), base_set), base_set); });
      // The strands regrow as in the app (LiveHairstyle): into the storage of the strands
      // they replace, after a first growth for the initial style.
      mr.setup_ms += bench::time_ms([&] { mr.grower.grow(SampledField(g, mr.solver->field()), roots[1], mr.strands); });
      mr.current = base_set;
    }
    auto run = [&](MethodRun& mr, const StreamCurve& curve) {
      Stage st;
      ConstraintSet next;
      ConstraintDiff d;
      st.diff_ms = bench::time_ms([&] {
        auto groups = base;
        groups.push_back(curve.constraints(g));
        next = ConstraintSet::merge(groups);
        d = diff(mr.current, next);
      });
      st.field = mr.solver->apply(d, next);
      mr.current = next;
      st.grow_ms = bench::time_ms([&] { mr.grower.grow(SampledField(g, mr.solver->field()), roots[1], mr.strands); });
      st.total_ms = st.diff_ms + st.field.total_ms + st.grow_ms;
      return st;
    };
    for (int rep = 0; rep < repetitions; ++rep)
      for (MethodRun& mr : methods) {
        mr.runs[0].push_back(run(mr, stroke));
        mr.runs[1].push_back(run(mr, edited));
        mr.solver->apply(diff(mr.current, base_set), base_set);  // back to the base style
        mr.current = base_set;
      }
    for (MethodRun& mr : methods)
      for (int e = 0; e < 2; ++e) {
        const char* name = e == 0 ? "stroke" : "edit";
        std::vector<Stage> runs = mr.runs[e];
        std::vector<double> totals;
        for (const Stage& st : runs) totals.push_back(st.total_ms);
        std::sort(runs.begin(), runs.end(), [](const Stage& x, const Stage& y) { return x.total_ms < y.total_ms; });
        const Stage& st = runs[runs.size() / 2];  // the median repetition
        const FieldSolveReport& r = st.field;
        table.row({std::to_string(g.num_nodes()), to_string(mr.method), name,
                   std::to_string(r.added) + "/" + std::to_string(r.removed), bench::fmt(st.diff_ms),
                   bench::fmt(r.update_ms), bench::fmt(r.solve_ms), std::to_string(r.iterations),
                   bench::fmt(st.grow_ms), bench::fmt(st.total_ms), r.detail});
        out["runs"].push_back({{"unknowns", g.num_nodes()},
                               {"method", to_string(mr.method)},
                               {"edit", name},
                               {"added", r.added},
                               {"removed", r.removed},
                               {"diff_ms", st.diff_ms},
                               {"update_ms", r.update_ms},
                               {"solve_ms", r.solve_ms},
                               {"iterations", r.iterations},
                               {"error_estimate", r.error_estimate},
                               {"grow_20k_ms", st.grow_ms},
                               {"total_20k_ms", st.total_ms},
                               {"total_20k_ms_repetitions", totals},
                               {"setup_ms", mr.setup_ms},
                               {"detail", r.detail}});
      }
    for (auto& row : skipped) table.row(row);
    // Thesis and refactorization against the multigrid path, repetition by repetition.
    for (const MethodRun& mr : methods) {
      if (mr.method == FieldMethod::Multigrid) continue;
      for (int e = 0; e < 2; ++e) {
        std::vector<double> ratio;
        for (int rep = 0; rep < repetitions; ++rep)
          ratio.push_back(mr.runs[e][rep].total_ms / methods[0].runs[e][rep].total_ms);
        out["ratios"].push_back({{"unknowns", g.num_nodes()},
                                 {"method", to_string(mr.method)},
                                 {"edit", e == 0 ? "stroke" : "edit"},
                                 {"over_multigrid", ratio},
                                 {"median", bench::median(ratio)}});
        std::ostringstream line;
        line.setf(std::ios::fixed);
        line.precision(1);
        line << to_string(mr.method) << " / multigrid at " << g.num_nodes() << ", " << (e == 0 ? "stroke" : "edit")
             << ": median " << bench::median(ratio) << "x (";
        for (double q : ratio) line << ' ' << q;
        line << " )";
        ratio_lines.push_back(line.str());
      }
    }
    {
      const MethodRun& mr = methods[0];
      const SampledField f(g, mr.solver->field());
      for (size_t k = 0; k < roots.size(); ++k) {
        // Regrowth into reused storage (the interactive loop), and into fresh allocations
        // (grow_strands), whose page faults are the difference.
        Strands s;
        StrandGrower reuse;
        std::vector<double> t, fresh;
        reuse.grow(f, roots[k], s);
        for (int rep = 0; rep < 3; ++rep) {
          t.push_back(bench::time_ms([&] { reuse.grow(f, roots[k], s); }));
          fresh.push_back(bench::time_ms([&] { const Strands once = grow_strands(f, roots[k]); }));
        }
        growth.row({std::to_string(g.num_nodes()), std::to_string(roots[k].size()), std::to_string(s.segments()),
                    bench::fmt(bench::median(t)), bench::fmt(bench::median(fresh))});
        out["growth"].push_back({{"unknowns", g.num_nodes()},
                                 {"strands", roots[k].size()},
                                 {"segments", s.segments()},
                                 {"ms", bench::median(t)},
                                 {"fresh_allocation_ms", bench::median(fresh)}});
      }
    }
    table.print();
    for (const std::string& line : ratio_lines) std::printf("%s\n", line.c_str());
    ratio_lines.clear();
    std::printf("\n");
  }
  growth.print();
  out["peak_rss_mib"] = bench::peak_rss_mib();
  bench::write_results("hair_sketch", out);
  return 0;
}
