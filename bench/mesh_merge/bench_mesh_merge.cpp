// Poisson mesh merging timings (thesis Table 3.1), configuration-independent, default options:
//  - synthetic: a bumpy spherical cap (the "head") merged onto an open cylinder (the "neck"),
//    10K to 200K source vertices;
//  - real: assets/external/armadillo.off (Loop-subdivided 0, 1 or 2 times) cut by a plane
//    across its body, the upper part merged back onto the lower one: 16K, 53K and 212K source
//    vertices, a scanned mesh's irregular valences and a target as large as the source.
// Targets: 16K source <= 0.5 s and 50K <= 1.5 s end to end.
// Usage: bench_mesh_merge [--quick]   (--quick: the 10K and 16K cases only)
// Besides the in-process repetitions, each case is merged once in a fresh process ("cold"):
// what `lapis merge` pays, with every page of its memory new to the process.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_merge/cut.h"
#include "lapis/mesh_merge/merge.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis_bench.h"
#include "memory_bandwidth.h"

using namespace lapis;
using namespace lapis::mesh_merge;

namespace {

struct Case {
  const char* name;
  // Synthetic (mesh == nullptr): icosphere level of the cap, cut at z = cut (vertex share
  // (1 - cut) / 2). Real: the mesh in assets/external, its Loop subdivision levels, the cut
  // plane across y at `cut` of the height.
  int subdivisions;
  double cut;
  const char* mesh = nullptr;
  bool quick = false;  // run by --quick
};

// Cap with bumps (details the merge must keep), boundary near z = cut_z.
geometry::TriMesh cap(const Case& c) {
  geometry::TriMesh s = geometry::make_icosphere(c.subdivisions);
  for (int v = 0; v < s.num_vertices(); ++v) {
    const Eigen::Vector3d p = s.V.row(v);
    s.V.row(v) *= 1.0 + 0.03 * std::sin(17 * p.x()) * std::sin(13 * p.y()) * std::sin(11 * p.z());
  }
  return cut_by_plane(s, {0, 0, c.cut}, {0, 0, 1}).above;
}

int loop_max_x(const geometry::TriMesh& m, bool top) {
  const geometry::Connectivity conn(m);
  const auto& loops = conn.boundary_loops();
  size_t pick = 0;
  for (size_t l = 1; l < loops.size(); ++l)
    if ((m.V(loops[l][0], 2) > m.V(loops[pick][0], 2)) == top) pick = l;
  int best = loops[pick][0];
  for (int v : loops[pick])
    if (m.V(v, 0) > m.V(best, 0)) best = v;
  return best;
}

struct Inputs {
  geometry::TriMesh source, target;
  std::vector<LoopPair> pairs;
};

Inputs synthetic_inputs(const Case& c) {
  Inputs in;
  in.source = cap(c);
  const int around = static_cast<int>(std::sqrt(double(in.source.num_vertices())) * 2);
  in.target = geometry::make_cylinder(around, around / 4, 0.8, 2.0);
  in.pairs = {LoopPair{{KeyCorrespondence{loop_max_x(in.source, false), loop_max_x(in.target, true)}}}};
  return in;
}

// The part above the plane onto the part below, keyed at the same vertex of the cut mesh.
Inputs real_inputs(const Case& c) {
  geometry::TriMesh m = geometry::read_mesh(std::string(LAPIS_SOURCE_DIR) + "/assets/external/" + c.mesh + ".off");
  if (c.subdivisions > 0) m = geometry::loop_subdivide(m, c.subdivisions);
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff();
  PlaneCut cut = cut_by_plane(m, lo + c.cut * (hi - lo), {0, 1, 0});
  const int key = geometry::Connectivity(cut.above).boundary_loops().at(0)[0];
  const auto& below = cut.below_to_mesh;
  const int key_below = static_cast<int>(std::find(below.begin(), below.end(), cut.above_to_mesh[key]) - below.begin());
  Inputs in;
  in.source = std::move(cut.above);
  in.target = std::move(cut.below);
  in.pairs = {LoopPair{{KeyCorrespondence{key, key_below}}}};
  return in;
}

Inputs inputs(const Case& c) { return c.mesh ? real_inputs(c) : synthetic_inputs(c); }

// One merge of the case in a fresh process (this executable with --cold NAME), its total ms;
// negative if the child failed.
double cold_merge_ms(const Case& c) {
  // /proc/self/exe resolved here: in popen's shell it would name the shell.
  const std::string command = std::filesystem::read_symlink("/proc/self/exe").string() + " --cold '" + c.name + "'";
  FILE* child = popen(command.c_str(), "r");
  if (!child) return -1;
  double ms = -1;
  if (std::fscanf(child, "%lf", &ms) != 1) ms = -1;
  return pclose(child) == 0 ? ms : -1;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(argc, argv, {"--quick", "--cold"},
                              "usage: bench_mesh_merge [--quick]\n"
                              "  Poisson merging timings (thesis Table 3.1); --quick: the 10K and 16K cases only\n");
  const std::vector<Case> cases = {{"10K", 6, 0.5, nullptr, true},
                                   {"16K", 7, 0.8, nullptr, true},
                                   {"50K", 7, 0.39},
                                   {"200K", 8, 0.39},
                                   {"armadillo 16K", 0, 0.5, "armadillo", true},
                                   {"armadillo 53K", 1, 0.68, "armadillo"},
                                   {"armadillo 212K", 2, 0.68, "armadillo"}};
  if (argc > 2 && std::strcmp(argv[1], "--cold") == 0) {
    for (const Case& c : cases)
      if (std::strcmp(c.name, argv[2]) == 0) {
        const Inputs in = inputs(c);
        std::printf("%.3f\n", merge(in.source, in.target, in.pairs).timings.total_ms);
        return 0;
      }
    return 1;
  }
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  bench::Table table({"source", "V_src", "V_tgt", "boundary", "setup ms", "solve ms", "zip ms", "smooth ms", "total ms",
                      "cold ms", "cpu ms", "re-merge ms", "seam ok", "residual"});
  nlohmann::json results = nlohmann::json::array();
  const bench::MemoryBandwidth bandwidth = bench::measure_memory_bandwidth();
  std::printf("memory read bandwidth: %.1f GB/s on one thread, %.1f GB/s on %d\n\n", bandwidth.one_thread_gbs,
              bandwidth.all_threads_gbs, bandwidth.threads);
  for (const Case& c : cases) {
    if (quick && !c.quick) continue;
    const Inputs in = inputs(c);
    const geometry::TriMesh& src = in.source;
    const geometry::TriMesh& tgt = in.target;
    const std::vector<LoopPair>& pairs = in.pairs;
    std::vector<double> total, cpu;
    MergeResult r;
    const int reps = src.num_vertices() < 100000 ? 3 : 1;  // the 200K case takes seconds
    for (int rep = 0; rep < reps; ++rep) {
      // Process CPU time beside wall time: this machine is shared, and wall time under load
      // can be several times the CPU time the merge needs.
      const std::clock_t c0 = std::clock();
      r = merge(src, tgt, pairs);
      cpu.push_back(1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC);
      total.push_back(r.timings.total_ms);
    }
    // Precompute once, merge again with the key moved three vertices along the source loop:
    // what an interactive session pays per change.
    Merger merger(src);
    std::vector<LoopPair> moved = pairs;
    {
      const geometry::Connectivity cs(src);
      const auto& loop = cs.boundary_loops()[0];
      const auto at = std::find(loop.begin(), loop.end(), moved[0].keys[0].source) - loop.begin();
      moved[0].keys[0].source = loop[static_cast<size_t>(at + 3) % loop.size()];
    }
    const double remerge_ms = merger.merge(tgt, moved).timings.total_ms;
    const double cold_ms = cold_merge_ms(c);
    const SeamQuality q = seam_quality(tgt, r);
    const DetailPreservation d = detail_preservation(src, r);
    const int boundary = static_cast<int>(r.source_boundary.size());
    table.row({c.name, std::to_string(src.num_vertices()), std::to_string(tgt.num_vertices()), std::to_string(boundary),
               bench::fmt(r.timings.setup_ms), bench::fmt(r.timings.solve_ms), bench::fmt(r.timings.zip_ms),
               bench::fmt(r.timings.smooth_ms), bench::fmt(bench::median(total)), bench::fmt(cold_ms),
               bench::fmt(bench::median(cpu)), bench::fmt(remerge_ms), q.valid() ? "yes" : "NO",
               bench::fmt(d.laplacian_residual, 4)});
    results.push_back({{"case", c.name},
                       {"source_vertices", src.num_vertices()},
                       {"target_vertices", tgt.num_vertices()},
                       {"boundary_vertices", boundary},
                       {"refine_levels", r.refine_levels},
                       {"setup_ms", r.timings.setup_ms},
                       {"solve_ms", r.timings.solve_ms},
                       {"zip_ms", r.timings.zip_ms},
                       {"smooth_ms", r.timings.smooth_ms},
                       {"total_ms_median", bench::median(total)},
                       {"repetitions", reps},
                       {"cold_process_ms", cold_ms},
                       {"cpu_ms_median", bench::median(cpu)},
                       {"precompute_ms", merger.precompute_ms()},
                       {"remerge_ms", remerge_ms},
                       {"seam_valid", q.valid()},
                       {"min_strip_angle_deg", q.min_strip_angle_deg},
                       {"laplacian_residual", d.laplacian_residual},
                       {"first_factor_nnz", r.solver.first_factor_nnz},
                       {"second_factor_nnz", r.solver.second_factor_nnz}});
  }
  table.print();
  if (!quick)
    bench::write_results(
        "mesh_merge",
        {{"cases", results}, {"memory_bandwidth", bandwidth.to_json()}, {"peak_rss_mib", bench::peak_rss_mib()}});
  return 0;
}
