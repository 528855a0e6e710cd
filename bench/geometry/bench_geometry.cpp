// Geometry benchmark: the armadillo Loop-subdivided to 1.66M vertices is saved and loaded
// (binary PLY and ASCII OFF), validated, given connectivity, a cotangent Laplacian and a BVH
// that casts 1M rays; plus 1M 3x3 SVDs against Eigen's JacobiSVD. Every step runs with 1 and
// 2 OpenMP threads (median of repeats), printed as a table and saved to
// bench/results/geometry.json.
#include <omp.h>
#include <sys/resource.h>

#include <Eigen/SVD>
#include <cstdio>
#include <cstdlib>
#include <random>

#include "lapis/geometry/bvh.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/polar.h"
#include "lapis/geometry/procedural.h"
#include "lapis_bench.h"

using namespace lapis::geometry;
namespace bench = lapis::bench;

namespace {

double cpu_ms() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return 1e3 * (u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-3 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Timing {
  double wall_ms;    // median over repeats
  double cpu_share;  // process CPU time / (wall time x threads): below 1 when others use the cores
};

// Median wall time of f() over repeats runs, with `threads` OpenMP threads, and how much of
// the requested cores the process actually got (the machine is shared: the share says how
// far the wall times are inflated).
template <class F>
Timing timed(int threads, int repeats, F&& f) {
  omp_set_num_threads(threads);
  std::vector<double> t;
  const double cpu0 = cpu_ms();
  for (int r = 0; r < repeats; ++r) t.push_back(bench::time_ms(f));
  double total = 0;
  for (double x : t) total += x;
  return {bench::median(t), (cpu_ms() - cpu0) / (total * threads)};
}

struct Rays {
  std::vector<Eigen::Vector3d> origin, direction;
};

// Rays from a sphere around the mesh towards random points of its bounding box: about
// half hit, as in picking.
Rays make_rays(const TriMesh& m, int n) {
  const Eigen::Vector3d lo = m.V.colwise().minCoeff(), hi = m.V.colwise().maxCoeff(), c = 0.5 * (lo + hi);
  const double r = (hi - lo).norm();
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0, 1);
  Rays rays;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d o = c + r * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const Eigen::Vector3d target = lo + (hi - lo).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    rays.origin.push_back(o);
    rays.direction.push_back(target - o);
  }
  return rays;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(
      argc, argv, {},
      "usage: bench_geometry\n  save/load, validation, connectivity, cotangent Laplacian, BVH rays and 3x3 SVDs on "
      "the\n  armadillo Loop-subdivided to 1.66M vertices, 1 and 2 threads; writes bench/results/geometry.json\n");
  const auto armadillo = std::filesystem::path(LAPIS_SOURCE_DIR) / "assets/external/armadillo.off";
  if (!std::filesystem::exists(armadillo)) {
    std::fprintf(stderr, "bench_geometry: %s missing: run scripts/setup\n", armadillo.c_str());
    return 1;
  }
  const int max_threads = std::min(2, omp_get_num_procs());
  std::printf("bench_geometry: %d hardware threads; subdividing the armadillo...\n", omp_get_num_procs());
  const TriMesh big = loop_subdivide(read_mesh(armadillo), 3);
  const auto dir = std::filesystem::temp_directory_path() / "lapis_bench_geometry";
  std::filesystem::create_directories(dir);
  const auto ply = dir / "armadillo3.ply", off = dir / "armadillo3.off";
  write_ply(ply, big);
  write_off(off, big);
  const std::string size = std::to_string(big.num_vertices()) + " V, " + std::to_string(big.num_faces()) + " F";

  bench::Table table({"step", "size", "1 thread ms", "CPU share", "2 threads ms", "CPU share", "speedup"});
  nlohmann::json results;
  results["mesh"] = {{"source", "armadillo.off Loop-subdivided 3 times"},
                     {"vertices", big.num_vertices()},
                     {"faces", big.num_faces()}};
  auto run = [&](const std::string& step, const std::string& what, int repeats, auto&& f) {
    Timing t[3] = {};
    for (int threads = 1; threads <= max_threads; ++threads) t[threads] = timed(threads, repeats, f);
    const double speedup = t[max_threads].wall_ms > 0 ? t[1].wall_ms / t[max_threads].wall_ms : 0;
    table.row({step, what, bench::fmt(t[1].wall_ms), bench::fmt(t[1].cpu_share, 2), bench::fmt(t[max_threads].wall_ms),
               bench::fmt(t[max_threads].cpu_share, 2), bench::fmt(speedup, 2)});
    results["steps"].push_back({{"step", step},
                                {"size", what},
                                {"ms_1_thread", t[1].wall_ms},
                                {"cpu_share_1_thread", t[1].cpu_share},
                                {"ms_2_threads", t[max_threads].wall_ms},
                                {"cpu_share_2_threads", t[max_threads].cpu_share},
                                {"speedup", speedup}});
    std::printf("  %-28s %10.1f ms / %10.1f ms\n", step.c_str(), t[1].wall_ms, t[max_threads].wall_ms);
    std::fflush(stdout);
  };

  TriMesh loaded;
  run("read_ply (binary)", size, 3, [&] { loaded = read_ply(ply); });
  run("read_off (ASCII)", size, 1, [&] { loaded = read_off(off); });
  run("validate", size, 3, [&] { validate(loaded); });
  run("Connectivity", size, 3, [&] { Connectivity c(loaded); });
  run("cotan_laplacian", size, 3, [&] { cotan_laplacian(loaded); });
  std::optional<Bvh> bvh;
  run("Bvh build", size, 3, [&] { bvh.emplace(loaded); });
  const int num_rays = 1000000;
  const Rays rays = make_rays(loaded, num_rays);
  int hits = 0;
  run("Bvh 1M rays", "1000000 rays", 3, [&] {
    int h = 0;
#pragma omp parallel for schedule(dynamic, 4096) reduction(+ : h)
    for (int i = 0; i < num_rays; ++i) h += bvh->intersect(rays.origin[i], rays.direction[i]).has_value();
    hits = h;
  });
  results["ray_hit_fraction"] = static_cast<double>(hits) / num_rays;

  const int num_svd = 1000000;
  std::vector<Eigen::Matrix3d> matrices(num_svd);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (auto& M : matrices)
    for (int k = 0; k < 9; ++k) M(k / 3, k % 3) = u(rng);
  double sink = 0;
  run("svd3", "1000000 matrices", 3, [&] {
    double s = 0;
#pragma omp parallel for schedule(static) reduction(+ : s)
    for (int i = 0; i < num_svd; ++i) {
      Eigen::Matrix3d U, V;
      Eigen::Vector3d S;
      svd3(matrices[i], U, S, V);
      s += S[0] + U(0, 0);
    }
    sink += s;
  });
  run("Eigen JacobiSVD<Matrix3d>", "1000000 matrices", 3, [&] {
    double s = 0;
#pragma omp parallel for schedule(static) reduction(+ : s)
    for (int i = 0; i < num_svd; ++i) {
      const Eigen::JacobiSVD<Eigen::Matrix3d> svd(matrices[i], Eigen::ComputeFullU | Eigen::ComputeFullV);
      s += svd.singularValues()[0] + svd.matrixU()(0, 0);
    }
    sink += s;
  });
  run("polar_rotation", "1000000 matrices", 3, [&] {
    double s = 0;
#pragma omp parallel for schedule(static) reduction(+ : s)
    for (int i = 0; i < num_svd; ++i) s += polar_rotation(matrices[i])(0, 0);
    sink += s;
  });

  std::printf("\n");
  table.print();
  std::printf("ray hit fraction %.3f, peak RSS %.0f MiB (checksum %g)\n", static_cast<double>(hits) / num_rays,
              bench::peak_rss_mib(), sink);
  results["peak_rss_mib"] = bench::peak_rss_mib();
  results["hardware_threads"] = omp_get_num_procs();
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) > 0) results["load_average_1min"] = load[0];
  bench::write_results("geometry", results);
  std::filesystem::remove_all(dir);
  return 0;
}
