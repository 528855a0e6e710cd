// mesh_deform benchmark: setup seconds, per-frame milliseconds of a drag, ARAP milliseconds
// per iteration and peak memory of naive Laplacian, implicit Laplacian (thesis ch. 2), ARAP
// and edge-based Laplacian editing (Wang et al., edge and vertex domain), salient features in a
// solid subspace (Zhao et al.; salient_row.h has its stages), against CGAL's
// Surface_mesh_deformation (ORIGINAL_ARAP) on the same mesh, ROI and handle in the same run,
// with the last frame's distortion. Each (mesh, method) runs in its own child process so the
// peak memory is that method's alone.
//
//   bench_mesh_deform [--sizes 26k,52k,151k,416k,1m] [--methods naive,arap,...] [--implicit-large]
//
// Meshes: armadillo (26K), the mannequin-devil bust Loop-subdivided once (52K: the 50K
// implicit target), Loop-subdivided bunny (151K) and armadillo (416K), the man
// Loop-subdivided three times (1.1M). The implicit method runs at 416K and 1M only with
// --implicit-large (its factor would need several GB).
// Fixed region: the lowest 10% of the vertices along y; handle: the top 5%, rotated 45° about
// z around its centroid and moved 0.15 × the bounding-box diagonal along x over the drag.
#include <cstdio>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>

#include <omp.h>

#include "cgal_arap.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/naive_laplacian.h"
#include "lapis_bench.h"
#include "salient_row.h"

using namespace lapis;
using namespace lapis::mesh_deform;
using nlohmann::json;

namespace {

constexpr int kArapIterationsPerFrame = 5;

struct Size {
  std::string name, file;
  int loop_levels;
  int frames;       // Lapis methods
  int peer_frames;  // CGAL (each frame runs kArapIterationsPerFrame iterations)
};

const std::vector<Size> kSizes = {
    {"26k", "armadillo", 0, 100, 10}, {"52k", "mannequin-devil", 1, 50, 6},
    {"151k", "bunny00", 1, 20, 4},    {"416k", "armadillo", 2, 10, 3},
    {"1m", "man", 3, 5, 2},
};

TriMesh load(const Size& s) {
  TriMesh m = geometry::read_mesh(std::string(LAPIS_SOURCE_DIR) + "/assets/external/" + s.file + ".off");
  return s.loop_levels ? geometry::loop_subdivide(m, s.loop_levels) : m;
}

struct Setup {
  Selection sel;
  std::vector<Eigen::Matrix4d> drag;  // handle transform per frame, ending at the full one
};

Setup make_setup(const TriMesh& m, int frames) {
  const int n = m.num_vertices();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return m.V(a, 1) < m.V(b, 1); });
  const int fixed = n / 10, handle = n / 20;
  Setup s;
  s.sel.roi.assign(order.begin() + fixed, order.end());
  s.sel.region_handles.push_back(std::vector<int>(order.end() - handle, order.end()));
  std::sort(s.sel.roi.begin(), s.sel.roi.end());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int v : s.sel.region_handles[0]) c += m.V.row(v).transpose();
  c /= handle;
  const double diag = (m.V.colwise().maxCoeff() - m.V.colwise().minCoeff()).norm();
  for (int f = 1; f <= frames; ++f) {
    const double t = double(f) / frames;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(t * M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    T.topLeftCorner<3, 3>() = R;
    T.topRightCorner<3, 1>() = c - R * c + Eigen::Vector3d(0.15 * diag * t, 0, 0);
    s.drag.push_back(T);
  }
  return s;
}

// T applied to every rest position (#V by 3).
Vertices apply_to_rest(const TriMesh& m, const Eigen::Matrix4d& T) {
  return ((m.V * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose()).eval();
}

json run_one(const Size& size, const std::string& method) {
  const TriMesh m = load(size);
  json r = {{"mesh", size.name}, {"vertices", m.num_vertices()}, {"method", method}};
  const Setup s = make_setup(m, method == "cgal_arap" ? size.peer_frames : size.frames);
  if (method == "salient") {
    r.update(bench::salient_row(m, s.sel, s.drag, kArapIterationsPerFrame));
    return r;
  }
  if (method == "cgal_arap") {
    std::unique_ptr<peers::CgalArap> cgal;
    r["setup_s"] =
        bench::time_ms([&] { cgal = std::make_unique<peers::CgalArap>(m, s.sel.roi, s.sel.region_handles[0]); }) /
        1000.0;
    std::vector<double> per_it;
    for (const Eigen::Matrix4d& T : s.drag) {
      cgal->set_targets(apply_to_rest(m, T));
      per_it.push_back(bench::time_ms([&] { cgal->deform(kArapIterationsPerFrame, 0.0); }) / kArapIterationsPerFrame);
    }
    r["ms_per_iteration"] = bench::median(per_it);
    r["frames"] = static_cast<int>(s.drag.size());
  } else {
    std::unique_ptr<Deformer> d;
    ImplicitLaplacianDeformer* imp = nullptr;
    ArapDeformer* arap = nullptr;
    EdgeLaplacianDeformer* edge = nullptr;
    if (method == "edge" || method == "edge_vertex") {
      // The paper's defaults (S R1 on world axes, uniform weights, 4 iterations a frame);
      // edge_vertex: the same fits on vertex cells, the paper's §4 baseline.
      EdgeLaplacianOptions o;
      if (method == "edge_vertex") o.domain = LaplacianDomain::Vertices;
      d = std::make_unique<EdgeLaplacianDeformer>(m, o);
      edge = static_cast<EdgeLaplacianDeformer*>(d.get());
    }
    if (method == "naive") d = std::make_unique<NaiveLaplacianDeformer>(m);
    if (method == "implicit" || method == "implicit_backsub") {
      // implicit_backsub: Eq. 2.8 back-substituted every frame instead of combined from the
      // precomputed handle basis, to show both.
      ImplicitOptions o;
      if (method == "implicit_backsub") o.max_basis_columns = 0;
      d = std::make_unique<ImplicitLaplacianDeformer>(m, o);
      imp = static_cast<ImplicitLaplacianDeformer*>(d.get());
    }
    if (method == "arap" || method == "arap_1t") {
      // arap_1t: one OpenMP thread, to set beside CGAL, which runs on one.
      if (method == "arap_1t") omp_set_num_threads(1);
      ArapOptions o;
      o.max_iterations = kArapIterationsPerFrame;
      d = std::make_unique<ArapDeformer>(m, o);
      arap = static_cast<ArapDeformer*>(d.get());
    }
    d->set_selection(s.sel);
    r["setup_s"] = bench::time_ms([&] { d->precompute(); }) / 1000.0;
    std::vector<double> frame, first, polar, second, per_it, rot, solve;
    Vertices X;
    for (const Eigen::Matrix4d& T : s.drag) {
      frame.push_back(bench::time_ms([&] { X = d->deform(HandleTransforms{{T}, {}}); }));
      if (edge) {
        const EdgeLaplacianReport& e = edge->report();
        per_it.push_back(e.frame_ms / e.iterations);
        rot.push_back(e.fit_ms / e.iterations);
        solve.push_back(e.solve_ms / (e.iterations + 1));  // the first solve, then one per iteration
      }
      if (imp) {
        first.push_back(imp->report().first_solve_ms);
        polar.push_back(imp->report().polar_ms);
        second.push_back(imp->report().second_solve_ms);
      }
      if (arap) {
        per_it.push_back(arap->report().ms_per_iteration());
        rot.push_back(arap->report().rotations_ms / arap->report().iterations);
        solve.push_back(arap->report().solves_ms / arap->report().iterations);
      }
    }
    r["frames"] = s.drag.size();
    r["frame_ms"] = bench::median(frame);
    if (imp) {
      r["first_solve_ms"] = bench::median(first);
      r["polar_ms"] = bench::median(polar);
      r["second_solve_ms"] = bench::median(second);
      r["degenerate_vertices"] = imp->report().degenerate_vertices;
      r["basis_columns"] = imp->report().basis_columns;
      r["first_factor_nnz"] = imp->report().first_factor_nnz;
      r["second_factor_nnz"] = imp->report().second_factor_nnz;
    }
    if (arap || edge) {
      r["ms_per_iteration"] = bench::median(per_it);
      r["local_step_ms"] = bench::median(rot);
      r["global_step_ms"] = bench::median(solve);
    }
    if (edge) {
      r["iterations_per_frame"] = edge->report().iterations;
      r["rows"] = edge->report().rows;
      r["factor_nnz"] = edge->report().factor_nnz;
      r["last_move"] = edge->report().last_move;
    }
    const Distortion q = distortion(m, X);
    r["distortion"] = {{"edge_length_mean", q.edge_length.mean},
                       {"laplacian_length_mean", q.laplacian_length.mean},
                       {"angle_mean", q.angle.mean},
                       {"arap_energy", q.arap_energy}};
  }
  r["peak_rss_mib"] = bench::peak_rss_mib();
  return r;
}

std::string field(const json& r, const char* key, int digits = 1) {
  return r.contains(key) ? bench::fmt(r[key].get<double>(), digits) : "-";
}

// ",name," for a search in a comma-separated list. Appended, not `"," + std::string(...)`: GCC
// 12 warns (-Wrestrict) on that temporary's inlined copy.
std::string comma_delimited(const char* name) {
  std::string out(",");
  out.append(name).push_back(',');
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(
      argc, argv, {"--one", "--sizes", "--methods", "--implicit-large"},
      "usage: bench_mesh_deform [--sizes 26k,52k,151k,416k,1m] [--methods naive,arap,...] [--implicit-large]\n"
      "  setup, frame and peak memory per deformation method; writes bench/results/mesh_deform.json\n");
  if (argc == 4 && std::strcmp(argv[1], "--one") == 0) {
    for (const Size& s : kSizes)
      if (s.name == argv[2]) std::printf("%s\n", run_one(s, argv[3]).dump().c_str());
    return 0;
  }
  std::string sizes = "26k,52k,151k,416k,1m";
  std::string only = ",naive,implicit,implicit_backsub,arap,arap_1t,cgal_arap,edge,edge_vertex,salient,";
  bool implicit_large = false;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--sizes") == 0 && i + 1 < argc) sizes = argv[++i];
    if (std::strcmp(argv[i], "--methods") == 0 && i + 1 < argc) only = comma_delimited(argv[++i]);
    if (std::strcmp(argv[i], "--implicit-large") == 0) implicit_large = true;
  }
  json results = json::array();
  bench::Table table({"mesh", "#V", "method", "setup s", "frame ms", "ms/iter", "local ms", "solve ms", "eq2.8 ms",
                      "polar ms", "eq2.10 ms", "factor nnz", "edge len", "peak MiB"});
  for (const Size& s : kSizes) {
    if (sizes.find(s.name) == std::string::npos) continue;
    for (const char* method :
         {"naive", "implicit", "implicit_backsub", "arap", "arap_1t", "cgal_arap", "edge", "edge_vertex", "salient"}) {
      if (only.find(comma_delimited(method)) == std::string::npos) continue;
      if (std::string(method).starts_with("implicit") && (s.name == "416k" || s.name == "1m") && !implicit_large)
        continue;
      const std::string cmd = std::string(argv[0]) + " --one " + s.name + " " + method;
      const std::string out = bench::run_child(cmd, "bench_mesh_deform");
      if (out.empty()) continue;
      const json r = json::parse(out);
      results.push_back(r);
      table.row({s.name, std::to_string(r["vertices"].get<int>()), method, field(r, "setup_s", 2), field(r, "frame_ms"),
                 field(r, "ms_per_iteration"), field(r, "local_step_ms"), field(r, "global_step_ms"),
                 field(r, "first_solve_ms"), field(r, "polar_ms"), field(r, "second_solve_ms"),
                 r.contains("factor_nnz") ? std::to_string(r["factor_nnz"].get<long>()) : "-",
                 r.contains("distortion") ? bench::fmt(r["distortion"]["edge_length_mean"].get<double>(), 4) : "-",
                 field(r, "peak_rss_mib", 0)});
      std::fprintf(stderr, "%s %s done\n", s.name.c_str(), method);
    }
  }
  table.print();
  json doc = {{"arap_iterations_per_frame", kArapIterationsPerFrame},
              {"threads", std::getenv("OMP_NUM_THREADS") ? std::getenv("OMP_NUM_THREADS") : "default"},
              {"results", results}};
  bench::write_results("mesh_deform", doc);
  return 0;
}
