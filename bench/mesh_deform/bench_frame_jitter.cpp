// Frame-time spread of a drag on small meshes: the median, 95th percentile and worst frame of
// ARAP (5 iterations a frame) and implicit Laplacian editing, with one OpenMP thread and with
// the default team, each alone and beside busy processes that hold cores the way a renderer
// or another program does. A frame that waits on a descheduled or spinning thread shows in
// the worst column, not in the median.
//
//   bench_frame_jitter [--frames N] [--busy K] [--mesh NAME]   (K busy processes; default 0 and 1)
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>

#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lapis/geometry/io.h"
#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis_bench.h"

using namespace lapis;
using namespace lapis::mesh_deform;
using nlohmann::json;

namespace {

// Busy processes that spin until killed, to take cores away from the measured one.
class BusyProcesses {
 public:
  explicit BusyProcesses(int count) {
    for (int i = 0; i < count; ++i) {
      const pid_t pid = fork();
      if (pid == 0) {
        volatile unsigned long x = 0;
        for (;;) x = x + 1;
      }
      if (pid > 0) pids_.push_back(pid);
    }
  }
  ~BusyProcesses() {
    for (pid_t p : pids_) kill(p, SIGKILL);
    for (pid_t p : pids_) waitpid(p, nullptr, 0);
  }

 private:
  std::vector<pid_t> pids_;
};

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<size_t>(p * static_cast<double>(v.size())))];
}

// Fixed: the lowest 10% along y; handle: the top 5%, turned up to 45° about z over the drag.
Selection bottom_top(const TriMesh& m, Eigen::Vector3d& centroid) {
  const int n = m.num_vertices();
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return m.V(a, 1) < m.V(b, 1); });
  Selection sel;
  sel.roi.assign(order.begin() + n / 10, order.end());
  std::sort(sel.roi.begin(), sel.roi.end());
  sel.region_handles.push_back(std::vector<int>(order.end() - n / 20, order.end()));
  centroid.setZero();
  for (int v : sel.region_handles[0]) centroid += m.V.row(v).transpose();
  centroid /= static_cast<double>(sel.region_handles[0].size());
  return sel;
}

std::vector<double> drag_frames(Deformer& d, const TriMesh& m, int frames) {
  Eigen::Vector3d c;
  d.set_selection(bottom_top(m, c));
  d.precompute();
  std::vector<double> ms;
  for (int f = 1; f <= frames; ++f) {
    const double t = double(f) / frames;
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    const Eigen::Matrix3d R = Eigen::AngleAxisd(t * M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.topLeftCorner<3, 3>() = R;
    T.topRightCorner<3, 1>() = c - R * c;
    ms.push_back(bench::time_ms([&] { d.deform(HandleTransforms{{T}, {}}); }));
  }
  return ms;
}

std::unique_ptr<Deformer> make(const std::string& method, const TriMesh& m) {
  if (method == "implicit") return std::make_unique<ImplicitLaplacianDeformer>(m);
  ArapOptions o;
  o.max_iterations = 5;
  return std::make_unique<ArapDeformer>(m, o);
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(argc, argv, {"--frames", "--busy", "--mesh"},
                              "usage: bench_frame_jitter [--frames N] [--busy K] [--mesh NAME]\n"
                              "  frame-time spread of a drag, alone and beside K busy processes\n");
  int frames = 60;
  std::vector<int> busy_counts = {0, 1};
  std::vector<std::string> meshes = {"elephant", "dino", "camel", "armadillo"};
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::strcmp(argv[i], "--frames") == 0)
      frames = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--busy") == 0)
      busy_counts = {std::atoi(argv[++i])};
    else if (std::strcmp(argv[i], "--mesh") == 0)
      meshes = {argv[++i]};
  }
  const int team = omp_get_max_threads();
  json results = json::array();
  bench::Table table({"mesh", "#V", "method", "threads", "busy", "median ms", "p95 ms", "worst ms"});
  for (const std::string& name : meshes) {
    const TriMesh m = geometry::read_mesh(std::string(LAPIS_SOURCE_DIR) + "/assets/external/" + name + ".off");
    for (const char* method : {"arap", "implicit"})
      for (int busy : busy_counts)
        for (int threads : {1, team}) {
          omp_set_num_threads(threads);
          std::vector<double> ms;
          {
            BusyProcesses load(busy);
            ms = drag_frames(*make(method, m), m, frames);
          }
          const json r = {{"mesh", name},
                          {"vertices", m.num_vertices()},
                          {"method", method},
                          {"threads", threads},
                          {"busy_processes", busy},
                          {"median_ms", bench::median(ms)},
                          {"p95_ms", percentile(ms, 0.95)},
                          {"worst_ms", percentile(ms, 1.0)}};
          results.push_back(r);
          table.row({name, std::to_string(m.num_vertices()), method, std::to_string(threads), std::to_string(busy),
                     bench::fmt(r["median_ms"].get<double>()), bench::fmt(r["p95_ms"].get<double>()),
                     bench::fmt(r["worst_ms"].get<double>())});
        }
  }
  omp_set_num_threads(team);
  table.print();
  bench::write_results("frame_jitter", json{{"frames", frames}, {"cores", team}, {"results", results}});
  return 0;
}
