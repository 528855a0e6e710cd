// Handle-aware isolines benchmark (Au et al. 2007, Table 1): set-up split (field factorization
// and solves, isoline extraction and sampling, assembly of UᵀU and P), peak memory, t₂ (Eq. 10)
// and t₁ (Eq. 6) per iteration, iterations to converge, reconstruction and the converged drag
// frame, from the 28.8K bar to armadillo Loop×3 (1.66M), for H = 2, 3, 4, 12 handles and
// N = 10, 20, 40 isolines; the implicit method and ARAP on the same mesh and handles where they
// fit. Each row runs in its own child process so its peak memory is its own.
//
//   bench_isolines [--sizes bar,26k,151k,416k,1m,1.66m] [--configs h2n20,h3n20,...] [--peers]
//                  [--repeat N] [--results NAME]
//
// --repeat runs the whole set N times over, each row in its own process, and keeps each row's
// run with the median time per iteration (frame time for ARAP's and the implicit method's
// rows), with every run's figure and their minimum beside it. Sub-millisecond iterations move
// by a third between runs on a shared machine, and a slow spell lasts longer than a row: the
// repetitions take turns so that it falls on every size, not on one. --results names the JSON
// (bench/results/NAME.json; default mesh_deform_isolines).
//
// Fixed region: the lowest 10% of the vertices along the mesh's long axis (y; z for the bar);
// region handle 1: the top 5%, turned 45° about the cross axis and moved 0.15 × the diagonal;
// H = 3, 4 add the 5% at the lowest and highest x, moved 0.05 × the diagonal; H = 12 adds ten
// point handles spread over the free vertices, each moved 0.02 × the diagonal.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>

#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis_bench.h"

using namespace lapis;
using namespace lapis::mesh_deform;
using nlohmann::json;

namespace {

constexpr int kFrames = 10;

struct Size {
  std::string name, file;  // file "" = the procedural bar
  int loop_levels;
};

const std::vector<Size> kSizes = {{"bar", "", 0},           {"26k", "armadillo", 0}, {"151k", "bunny00", 1},
                                  {"416k", "armadillo", 2}, {"1m", "man", 3},        {"1.66m", "armadillo", 3}};

struct Config {
  std::string name;
  int region_handles;  // besides the fixed region
  int point_handles;
  int isolines;
};

const std::vector<Config> kConfigs = {{"h2n20", 1, 0, 20}, {"h3n20", 2, 0, 20}, {"h4n20", 3, 0, 20},
                                      {"h2n10", 1, 0, 10}, {"h2n40", 1, 0, 40}, {"h12n20", 1, 10, 20}};

TriMesh load(const Size& s) {
  if (s.file.empty()) return geometry::make_box_bar(20, 20, 350, 1.0, 1.0, 17.5);  // 28.8K vertices
  TriMesh m = geometry::read_mesh(std::string(LAPIS_SOURCE_DIR) + "/assets/external/" + s.file + ".off");
  return s.loop_levels ? geometry::loop_subdivide(m, s.loop_levels) : m;
}

struct Setup {
  Selection sel;
  std::vector<HandleTransforms> drag;  // per frame, ending at the full one
};

// The k-th lowest share `frac` of `candidates` by coordinate `axis` (highest with from_top).
std::vector<int> extreme(const TriMesh& m, std::vector<int> candidates, int axis, double frac, bool from_top) {
  std::stable_sort(candidates.begin(), candidates.end(), [&](int a, int b) { return m.V(a, axis) < m.V(b, axis); });
  const size_t k = static_cast<size_t>(frac * m.num_vertices());
  std::vector<int> out = from_top ? std::vector<int>(candidates.end() - k, candidates.end())
                                  : std::vector<int>(candidates.begin(), candidates.begin() + k);
  std::sort(out.begin(), out.end());
  return out;
}

Eigen::Matrix4d turn_and_move(const TriMesh& m, const std::vector<int>& h, double angle, const Eigen::Vector3d& axis,
                              const Eigen::Vector3d& move) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : h) c += m.V.row(v).transpose();
  c /= static_cast<double>(h.size());
  const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = R;
  T.topRightCorner<3, 1>() = c - R * c + move;
  return T;
}

Setup make_setup(const TriMesh& m, const Config& c, int axis) {
  const int n = m.num_vertices();
  std::vector<int> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::vector<int> low = extreme(m, all, axis, 0.10, false);
  std::vector<char> taken(n, 0);
  for (int v : low) taken[v] = 1;
  Setup s;
  for (int v = 0; v < n; ++v)
    if (!taken[v]) s.sel.roi.push_back(v);
  auto free_now = [&] {
    std::vector<int> f;
    for (int v : s.sel.roi)
      if (!taken[v]) f.push_back(v);
    return f;
  };
  auto add_region = [&](std::vector<int> h) {
    for (int v : h) taken[v] = 1;
    s.sel.region_handles.push_back(std::move(h));
  };
  add_region(extreme(m, free_now(), axis, 0.05, true));
  if (c.region_handles >= 2) add_region(extreme(m, free_now(), 0, 0.05, false));
  if (c.region_handles >= 3) add_region(extreme(m, free_now(), 0, 0.05, true));
  const std::vector<int> rest = free_now();
  for (int p = 0; p < c.point_handles; ++p)
    s.sel.point_handles.push_back(rest[(2 * p + 1) * rest.size() / (2 * c.point_handles)]);
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  const Eigen::Vector3d cross = axis == 2 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
  for (int f = 1; f <= kFrames; ++f) {
    const double t = double(f) / kFrames;
    HandleTransforms h;
    h.regions.push_back(turn_and_move(m, s.sel.region_handles[0], t * M_PI / 4, cross, {0.15 * diag * t, 0, 0}));
    for (size_t r = 1; r < s.sel.region_handles.size(); ++r)
      h.regions.push_back(turn_and_move(m, s.sel.region_handles[r], 0, cross, {0, 0.05 * diag * t, 0}));
    for (size_t p = 0; p < s.sel.point_handles.size(); ++p) h.points.emplace_back(0.02 * diag * t, 0, 0);
    s.drag.push_back(h);
  }
  return s;
}

const Size& size_named(const std::string& name) {
  for (const Size& s : kSizes)
    if (s.name == name) return s;
  throw std::runtime_error("unknown size " + name);
}

const Config& config_named(const std::string& name) {
  for (const Config& c : kConfigs)
    if (c.name == name) return c;
  throw std::runtime_error("unknown config " + name);
}

void add_isolines_figures(json& r, IsolinesDeformer& d, const Setup& s) {
  const IsolinesReport& p = d.report();
  r["setup_s"] = p.setup_ms / 1000.0;
  r["fields_factorize_s"] = p.fields_factorize_ms / 1000.0;
  r["fields_solve_s"] = p.fields_solve_ms / 1000.0;
  r["extraction_s"] = p.extraction_ms / 1000.0;
  r["assembly_s"] = p.assembly_ms / 1000.0;
  r["handles"] = p.handles;
  r["unknowns"] = p.unknowns;
  r["sampled_triangles"] = p.sampled_triangles;
  r["crossed_triangles"] = p.crossed_triangles;
  r["field_overshoot"] = p.field_overshoot;
  std::vector<double> frame, per_it, warm, first, iters, recon;
  for (const HandleTransforms& h : s.drag) {
    frame.push_back(bench::time_ms([&] { d.deform(h); }));
    per_it.push_back(p.iterate_ms / p.iterations);
    first.push_back(p.iteration_ms.front());
    for (size_t k = 1; k < p.iteration_ms.size(); ++k) warm.push_back(p.iteration_ms[k]);
    iters.push_back(p.iterations);
    recon.push_back(p.reconstruct_ms);
  }
  r["ms_per_iteration"] = bench::median(per_it);
  r["first_iteration_ms"] = bench::median(first);  // the frame's first, the reduced system out of cache
  if (!warm.empty()) r["warm_iteration_ms"] = bench::median(warm);
  r["iterations"] = bench::median(iters);
  r["iterations_max"] = *std::max_element(iters.begin(), iters.end());
  r["reconstruct_ms"] = bench::median(recon);
  r["frame_ms"] = bench::median(frame);
}

json run_one(const Size& size, const Config& c, const std::string& method) {
  const TriMesh m = load(size);
  const int axis = size.file.empty() ? 2 : 1;
  const Setup s = make_setup(m, c, axis);
  json r = {{"mesh", size.name},
            {"vertices", m.num_vertices()},
            {"config", c.name},
            {"method", method},
            {"isolines", c.isolines}};
  if (method == "reduced" || method == "full") {
    IsolinesOptions o;
    o.isolines = c.isolines;
    if (method == "full") {
      o.solve = IsolineSolve::Full;
      o.max_iterations = 3;  // t₁ is O(#V) per iteration; three of them measure it
    }
    IsolinesDeformer d(m, o);
    d.set_selection(s.sel);
    d.precompute();
    add_isolines_figures(r, d, s);
  } else {
    std::unique_ptr<Deformer> d;
    if (method == "implicit") d = std::make_unique<ImplicitLaplacianDeformer>(m);
    ArapDeformer* arap = nullptr;
    if (method == "arap") {
      ArapOptions o;
      o.max_iterations = 5;
      d = std::make_unique<ArapDeformer>(m, o);
      arap = static_cast<ArapDeformer*>(d.get());
    }
    d->set_selection(s.sel);
    r["setup_s"] = bench::time_ms([&] { d->precompute(); }) / 1000.0;
    std::vector<double> frame, per_it;
    for (const HandleTransforms& h : s.drag) {
      frame.push_back(bench::time_ms([&] { d->deform(h); }));
      if (arap) per_it.push_back(arap->report().ms_per_iteration());
    }
    r["frame_ms"] = bench::median(frame);
    if (arap) r["ms_per_iteration"] = bench::median(per_it);
  }
  r["peak_rss_mib"] = bench::peak_rss_mib();
  return r;
}

std::string field(const json& r, const char* key, int digits = 1) {
  return r.contains(key) ? bench::fmt(r[key].get<double>(), digits) : "-";
}

bool listed(const std::string& list, const std::string& name) {
  return ("," + list + ",").find("," + name + ",") != std::string::npos;
}

json run_child(const char* self, const std::string& size, const std::string& config, const std::string& method) {
  const std::string cmd = std::string(self) + " --one " + size + " " + config + " " + method;
  const std::string out = bench::run_child(cmd, "bench_isolines");
  return out.empty() ? json() : json::parse(out);
}

// The run with the median time per iteration (or frame time), every run's figure beside it.
json median_run(std::vector<json> runs) {
  auto figure = [](const json& r) {
    return r.contains("ms_per_iteration") ? r["ms_per_iteration"].get<double>() : r["frame_ms"].get<double>();
  };
  std::sort(runs.begin(), runs.end(), [&](const json& a, const json& b) { return figure(a) < figure(b); });
  json r = runs[runs.size() / 2];
  if (runs.size() > 1) {
    json all = json::array();
    for (const json& x : runs) all.push_back(figure(x));
    const bool per_iteration = r.contains("ms_per_iteration");
    r["runs"] = runs.size();
    r[per_iteration ? "ms_per_iteration_runs" : "frame_ms_runs"] = all;
    r[per_iteration ? "ms_per_iteration_min" : "frame_ms_min"] = figure(runs.front());
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(
      argc, argv, {"--one", "--sizes", "--configs", "--peers", "--repeat", "--results"},
      "usage: bench_isolines [--sizes bar,26k,151k,416k,1m,1.66m] [--configs h2n20,...] [--peers]\n"
      "                      [--repeat N] [--results NAME]\n"
      "  handle-aware isolines (Au et al. 2007, Table 1); writes bench/results/NAME.json\n");
  if (argc == 5 && std::strcmp(argv[1], "--one") == 0) {
    std::printf("%s\n", run_one(size_named(argv[2]), config_named(argv[3]), argv[4]).dump().c_str());
    return 0;
  }
  std::string sizes = "bar,26k,151k,416k,1m,1.66m", configs = "h2n20,h3n20,h4n20,h2n10,h2n40,h12n20";
  std::string results_name = "mesh_deform_isolines";
  bool peers = false;
  int repeat = 1;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--sizes") == 0 && i + 1 < argc) sizes = argv[++i];
    if (std::strcmp(argv[i], "--configs") == 0 && i + 1 < argc) configs = argv[++i];
    if (std::strcmp(argv[i], "--peers") == 0) peers = true;
    if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    if (std::strcmp(argv[i], "--results") == 0 && i + 1 < argc) results_name = argv[++i];
  }
  // Every row of the set, then the set run `repeat` times over.
  struct Row {
    const Size* size;
    const Config* config;
    std::string method;
    std::vector<json> runs;
  };
  std::vector<Row> rows;
  for (const Size& s : kSizes) {
    if (!listed(sizes, s.name)) continue;
    for (const Config& c : kConfigs) {
      if (!listed(configs, c.name)) continue;
      std::vector<std::string> methods{"reduced"};
      // t₁ and the full-space peers for the H = 2, N = 20 row; the implicit method's factor
      // would need several GB beyond 151K.
      if (c.name == "h2n20") methods.push_back("full");
      if (c.name == "h2n20" && peers) {
        methods.push_back("arap");
        if (s.name == "bar" || s.name == "26k" || s.name == "151k") methods.push_back("implicit");
      }
      for (const std::string& method : methods) rows.push_back({&s, &c, method, {}});
    }
  }
  for (int k = 0; k < repeat; ++k)
    for (Row& row : rows) {
      json run = run_child(argv[0], row.size->name, row.config->name, row.method);
      if (run.is_null()) continue;
      row.runs.push_back(std::move(run));
      std::fprintf(stderr, "%s %s %s done\n", row.size->name.c_str(), row.config->name.c_str(), row.method.c_str());
    }
  json results = json::array();
  bench::Table table({"mesh", "#V", "config", "method", "setup s", "fields s", "extract s", "assembly s", "n_tri",
                      "ms/iter", "1st ms", "warm ms", "iters", "recon ms", "frame ms", "peak MiB"});
  for (Row& row : rows) {
    if (row.runs.empty()) continue;
    const json r = median_run(std::move(row.runs));
    results.push_back(r);
    const double fields = r.contains("fields_factorize_s")
                              ? r["fields_factorize_s"].get<double>() + r["fields_solve_s"].get<double>()
                              : -1;
    table.row(
        {row.size->name, std::to_string(r["vertices"].get<int>()), row.config->name, row.method, field(r, "setup_s", 2),
         fields >= 0 ? bench::fmt(fields, 2) : "-", field(r, "extraction_s", 2), field(r, "assembly_s", 2),
         r.contains("sampled_triangles") ? std::to_string(r["sampled_triangles"].get<int>()) : "-",
         field(r, "ms_per_iteration", 2), field(r, "first_iteration_ms", 2), field(r, "warm_iteration_ms", 3),
         field(r, "iterations", 0), field(r, "reconstruct_ms"), field(r, "frame_ms"), field(r, "peak_rss_mib", 0)});
  }
  table.print();
  bench::write_results(results_name, {{"frames", kFrames}, {"repeat", repeat}, {"results", results}});
  return 0;
}
