// The hair-sketching system of thesis §4.4: (DᵀD + ω² Σ_{i∈C} e_i e_iᵀ) on an N³ grid,
// ω = 100, ~2.5% of the nodes constrained. Per N: analysis, supernodal (and simplicial)
// factorization, a 3-RHS solve, and modifying k constraints (half added, half removed) by
// update/downdate, by refactorization and by the automatic choice; the peer a libigl user
// would get (Eigen SimplicialLDLT on the new matrix). Then Lapis' solve kernel against
// cholmod_solve on surface-mesh factors (the armadillo). Prints tables, writes
// bench/results/solver.json.
//
//   bench_solver [--sizes 24,32,37,48] [--with-64] [--quick]
#include <Eigen/SparseCholesky>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "grid_matrices.h"
#include "lapis/geometry/io.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/solver/cholesky.h"
#include "lapis/solver/updatable_cholesky.h"
#include "lapis_bench.h"
#include "memory_bandwidth.h"

using namespace lapis;
using namespace lapis::solver;
using namespace lapis::solver::testing;
using lapis::bench::fmt;
using lapis::bench::time_ms;

namespace {

constexpr double kOmega2 = 100.0 * 100.0;  // ω = 100, thesis §4.4.1
constexpr double kMinuteMs = 60000.0;

// Which BLAS the process really loaded (CHOLMOD's supernodal speed depends on it).
std::string loaded_blas() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    if (line.find("openblas") != std::string::npos) return "OpenBLAS";
    if (line.find("libblas.so") != std::string::npos) {
      const auto p = line.find('/');
      return "reference BLAS (" + line.substr(p) + ")";
    }
  }
  return "unknown";
}

std::vector<int> parse_sizes(const char* s) {
  std::vector<int> out;
  std::string token;
  for (const char* c = s;; ++c) {
    if (*c == ',' || *c == 0) {
      if (!token.empty()) out.push_back(std::stoi(token));
      token.clear();
      if (*c == 0) break;
    } else {
      token += *c;
    }
  }
  return out;
}

struct Edit {
  std::vector<int> indices;
  std::vector<double> forward, backward;  // weights that apply the edit and undo it
};

// k/2 unconstrained nodes become constrained, k/2 constrained nodes are released.
Edit make_edit(const Eigen::VectorXd& weights, int k) {
  Edit e;
  const int n = static_cast<int>(weights.size());
  int added = 0, removed = 0;
  for (int i = 7; i < n && (added < k / 2 || removed < k - k / 2); i += 13) {
    const bool on = weights[i] > 0;
    if (!on && added < k / 2) {
      e.indices.push_back(i), e.forward.push_back(kOmega2), e.backward.push_back(0.0), ++added;
    } else if (on && removed < k - k / 2) {
      e.indices.push_back(i), e.forward.push_back(0.0), e.backward.push_back(kOmega2), ++removed;
    }
  }
  // Not enough constrained nodes on the stride: release any constrained node.
  for (int i = 0; i < n && removed < k - k / 2; ++i)
    if (weights[i] > 0 && std::find(e.indices.begin(), e.indices.end(), i) == e.indices.end())
      e.indices.push_back(i), e.forward.push_back(0.0), e.backward.push_back(kOmega2), ++removed;
  return e;
}

// Median milliseconds of a 3-RHS solve by Lapis' kernel and by cholmod_solve on the same
// matrix, interleaved.
std::pair<double, double> solve_kernels_ms(const SparseMatrix& A) {
  Cholesky lapis_kernel, by_cholmod({Backend::Cholmod, FactorKind::Supernodal, 0, /*cholmod_solve=*/true});
  lapis_kernel.compute(A);
  by_cholmod.compute(A);
  const DenseMatrix B = DenseMatrix::Random(A.rows(), 3);
  std::vector<double> ours, theirs;
  for (int rep = 0; rep < 15; ++rep) {
    ours.push_back(time_ms([&] { lapis_kernel.solve(B); }));
    theirs.push_back(time_ms([&] { by_cholmod.solve(B); }));
  }
  return {bench::median(ours), bench::median(theirs)};
}

// The solve kernels on surface-mesh factors: the armadillo's cotangent Laplacian (ARAP's
// global step) and its square (the stencil width of the implicit method's systems).
nlohmann::json mesh_solve_table() {
  const auto path = std::filesystem::path(LAPIS_SOURCE_DIR) / "assets/external/armadillo.off";
  if (!std::filesystem::exists(path)) return nullptr;
  const geometry::TriMesh mesh = geometry::read_mesh(path);
  const SparseMatrix L = -geometry::cotan_laplacian(mesh);
  SparseMatrix pinned = L, squared = SparseMatrix(L.transpose()) * L;
  for (int i = 0; i < L.rows(); i += 50) pinned.coeffRef(i, i) += 1, squared.coeffRef(i, i) += 1;  // definite
  pinned.makeCompressed();
  squared.makeCompressed();
  nlohmann::json out = nlohmann::json::array();
  bench::Table table({"armadillo (26K)", "solve3 ms", "cholmod solve3 ms", "ratio"});
  for (const auto& [name, A] : {std::pair<const char*, const SparseMatrix*>{"cotan L", &pinned}, {"L^T L", &squared}}) {
    const auto [ours, theirs] = solve_kernels_ms(*A);
    out.push_back({{"matrix", name}, {"solve3_ms", ours}, {"cholmod_solve3_ms", theirs}});
    table.row({name, fmt(ours, 1), fmt(theirs, 1), fmt(theirs / ours, 2)});
  }
  std::printf("\n");
  table.print();
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  lapis::bench::check_options(
      argc, argv, {"--sizes", "--with-64", "--quick"},
      "usage: bench_solver [--sizes 24,32,37,48] [--with-64] [--quick]\n"
      "  the hair system's Cholesky factor, solves and update/downdate; writes bench/results/solver.json\n");
  std::vector<int> sizes = {24, 32, 37, 48};
  std::vector<int> ks = {10, 100, 1000};
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--sizes") && a + 1 < argc)
      sizes = parse_sizes(argv[++a]);
    else if (!std::strcmp(argv[a], "--with-64"))
      sizes.push_back(64);
    else if (!std::strcmp(argv[a], "--quick"))
      sizes = {24, 32}, ks = {10, 100};
    else {
      std::fprintf(stderr, "usage: bench_solver [--sizes 24,32,37,48] [--with-64] [--quick]\n");
      return 2;
    }
  }
  const std::string blas = loaded_blas();
  const bench::MemoryBandwidth bandwidth = bench::measure_memory_bandwidth();
  std::printf(
      "Lapis solver benchmark: hair-sketching normal matrix, omega = 100, BLAS: %s\n"
      "memory read bandwidth: %.1f GB/s on one thread, %.1f GB/s on %d\n\n",
      blas.c_str(), bandwidth.one_thread_gbs, bandwidth.all_threads_gbs, bandwidth.threads);

  nlohmann::json results;
  results["blas"] = blas;
  results["omega"] = 100;
  results["memory_bandwidth"] = bandwidth.to_json();
  bench::Table table({"N", "n", "nnz(L)", "ordering", "factor ms", "simplicial ms", "solve3 ms", "cholmod solve3",
                      "LDLt solve3", "k", "updown ms", "refactor ms", "auto ms", "auto chose", "k+solve ms",
                      "eigen ms"});
  double simplicial_ms_per_flop = 0, eigen_ms_per_flop = 0;

  for (int N : sizes) {
    const int n = N * N * N;
    const SparseMatrix D = grid_laplacian_3d(N);
    const SparseMatrix DtD = SparseMatrix(D.transpose()) * D;
    Eigen::VectorXd weights = Eigen::VectorXd::Zero(n);
    for (int i : spread_nodes(n, n / 40)) weights[i] = kOmega2;  // 2.5% constrained
    SparseMatrix A = DtD;
    for (int i = 0; i < n; ++i) A.coeffRef(i, i) += weights[i];
    A.makeCompressed();
    const DenseMatrix B = DenseMatrix::Random(n, 3);

    nlohmann::json r;
    r["N"] = N;
    r["n"] = n;

    Cholesky sup;
    sup.compute(A);
    r["nnz_L"] = sup.report().nnz_L;
    r["ordering"] = sup.report().ordering;
    r["analyze_ms"] = sup.report().analyze_ms;
    r["factor_ms"] = sup.report().factorize_ms;
    r["flops"] = sup.report().flops;
    // Lapis' parallel supernodal solve against cholmod_solve on the same factor, interleaved.
    Cholesky by_cholmod({Backend::Cholmod, FactorKind::Supernodal, 0, /*cholmod_solve=*/true});
    by_cholmod.compute(A);
    std::vector<double> solves, cholmod_solves;
    for (int rep = 0; rep < 7; ++rep) {
      solves.push_back(time_ms([&] { sup.solve(B); }));
      cholmod_solves.push_back(time_ms([&] { by_cholmod.solve(B); }));
    }
    const double solve3 = bench::median(solves);
    r["solve3_ms"] = solve3;
    r["cholmod_solve3_ms"] = bench::median(cholmod_solves);

    // Simplicial and Eigen factorizations: predicted from the flop count with the rate
    // measured at the previous size; skipped above a minute.
    const double flops = sup.report().flops;
    std::string simplicial_cell = "skipped";
    if (simplicial_ms_per_flop == 0 || simplicial_ms_per_flop * flops < kMinuteMs) {
      Cholesky simp({Backend::Cholmod, FactorKind::Simplicial});
      simp.compute(A);
      simplicial_ms_per_flop = simp.report().factorize_ms / flops;
      r["simplicial_factor_ms"] = simp.report().factorize_ms;
      simplicial_cell = fmt(simp.report().factorize_ms, 0);
    } else {
      r["simplicial_factor_ms"] = nullptr;
      r["simplicial_skipped"] = "predicted " + fmt(simplicial_ms_per_flop * flops / 1000, 0) + " s > 60 s";
    }
    std::string eigen_cell = "skipped";
    if (eigen_ms_per_flop == 0 || eigen_ms_per_flop * flops < kMinuteMs) {
      Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
      const double ms = time_ms([&] { ldlt.compute(A); });
      eigen_ms_per_flop = ms / flops;
      r["eigen_factor_ms"] = ms;
      eigen_cell = fmt(ms, 0);
    } else {
      r["eigen_factor_ms"] = nullptr;
      r["eigen_skipped"] = "predicted " + fmt(eigen_ms_per_flop * flops / 1000, 0) + " s > 60 s";
    }

    UpdatableCholesky upd;
    const double setup_ms = time_ms([&] { upd.compute(DtD, weights); });
    r["updatable_setup_ms"] = setup_ms;
    // The simplicial LDLᵀ solve the updatable factor uses (parallel over subtrees).
    std::vector<double> simplicial_solves;
    for (int rep = 0; rep < 5; ++rep) simplicial_solves.push_back(time_ms([&] { upd.solve(B); }));
    const double simplicial_solve3 = bench::median(simplicial_solves);
    r["simplicial_solve3_ms"] = simplicial_solve3;
    nlohmann::json modify;
    bool first_row = true;
    for (int k : ks) {
      const Edit edit = make_edit(weights, k);
      nlohmann::json mk;
      // The three methods interleaved, repetition by repetition, so that a slow spell of this
      // shared machine hits them alike; update/downdate and the automatic choice swap places
      // each time. Each timing is one application or one undo. A refactorization leaves a
      // freshly allocated factor behind whose first update pays for its page faults: one
      // untimed update/downdate follows it when that is cheap. The first, untimed run sets
      // the repetitions: as many as fit in about a second of update/downdate (three to eight),
      // and of refactorization three, or all when it takes under half a second.
      std::map<ModifyMethod, std::vector<double>> ms;
      std::string auto_choice;
      auto apply_and_undo = [&](ModifyMethod method) {
        upd.set_method(method);
        const double apply = upd.set_diagonal_weights(edit.indices, edit.forward).ms;
        if (method == ModifyMethod::Auto) auto_choice = to_string(upd.last_report().method);
        return std::pair{apply, upd.set_diagonal_weights(edit.indices, edit.backward).ms};
      };
      const double first_ms = apply_and_undo(ModifyMethod::UpdateDowndate).first;
      const int reps = std::clamp(static_cast<int>(1000.0 / std::max(first_ms, 1e-3)), 3, 8);
      for (int rep = 0; rep < reps; ++rep) {
        const bool refactorize = rep < 3 || bench::median(ms[ModifyMethod::Refactorize]) < 500;
        std::vector<std::pair<ModifyMethod, bool>> steps{{ModifyMethod::UpdateDowndate, true},
                                                         {ModifyMethod::Auto, true}};
        if (rep % 2) std::swap(steps[0], steps[1]);
        if (refactorize) {
          if (first_ms < 500) steps.insert(steps.begin(), {ModifyMethod::UpdateDowndate, false});
          steps.insert(steps.begin(), {ModifyMethod::Refactorize, true});
        }
        for (const auto& [method, timed] : steps) {
          const auto [apply, undo] = apply_and_undo(method);
          if (!timed) continue;
          ms[method].push_back(apply);
          ms[method].push_back(undo);
        }
      }
      for (const auto& [method, times] : ms) mk[to_string(method)] = bench::median(times);
      const double auto_ms = bench::median(ms[ModifyMethod::Auto]);
      const double best =
          std::min(bench::median(ms[ModifyMethod::UpdateDowndate]), bench::median(ms[ModifyMethod::Refactorize]));
      mk["auto_choice"] = auto_choice;
      mk["auto_over_best"] = auto_ms / best;
      upd.set_method(ModifyMethod::Auto);
      // Apply + solve, then undo; the median of five (the machine is shared and noisy).
      std::vector<double> plus_solves;
      for (int rep = 0; rep < 5; ++rep) {
        plus_solves.push_back(time_ms([&] {
          upd.set_diagonal_weights(edit.indices, edit.forward);
          upd.solve(B);
        }));
        upd.set_diagonal_weights(edit.indices, edit.backward);
      }
      const double plus_solve = bench::median(plus_solves);
      mk["modify_plus_solve3_ms"] = plus_solve;
      modify[std::to_string(k)] = mk;
      table.row({first_row ? std::to_string(N) : "", first_row ? std::to_string(n) : "",
                 first_row ? fmt(sup.report().nnz_L / 1e6, 1) + "M" : "", first_row ? sup.report().ordering : "",
                 first_row ? fmt(sup.report().factorize_ms, 0) : "", first_row ? simplicial_cell : "",
                 first_row ? fmt(solve3, 1) : "", first_row ? fmt(r["cholmod_solve3_ms"].get<double>(), 1) : "",
                 first_row ? fmt(simplicial_solve3, 1) : "", std::to_string(k),
                 fmt(mk["update/downdate"].get<double>(), 1), fmt(mk["refactorize"].get<double>(), 1), fmt(auto_ms, 1),
                 auto_choice, fmt(plus_solve, 1), first_row ? eigen_cell : ""});
      first_row = false;
    }
    r["modify_ms"] = modify;
    // The targets at the thesis' resolution (N = 37), as ratios measured in this run.
    if (modify.contains("10")) {
      const double m10 = modify["10"]["modify_plus_solve3_ms"].get<double>();
      r["speedup_k10_vs_refactor"] = sup.report().factorize_ms / m10;
      if (!r["eigen_factor_ms"].is_null()) r["speedup_k10_vs_eigen"] = r["eigen_factor_ms"].get<double>() / m10;
    }
    results["sizes"].push_back(r);
    std::fprintf(stderr, "N=%d done\n", N);
  }
  std::printf("\n");
  table.print();
  std::printf("\nk+solve: modifying k constraints with the automatic choice, then a 3-RHS solve.\n");
  results["mesh_solves"] = mesh_solve_table();
  bench::write_results("solver", results);
  return 0;
}
