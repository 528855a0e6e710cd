// The matrix-free normal operator (grid_stencil.h) on grids large enough to run in parallel,
// for thread counts that split the z-planes unevenly, into ranges of one plane, or leave
// threads without a plane; out of place and in place (the multigrid smoother overwrites its
// operand line by line), against the assembled matrix.
#include <doctest/doctest.h>
#include <omp.h>

#include <random>

#include "grid_stencil.h"
#include "lapis/hair_field/grid_operators.h"

using namespace lapis::hair_field;

TEST_CASE("hair_field: the plane-interleaved normal operator equals DtD + W for any thread split, in place too") {
  const int threads_before = omp_get_max_threads();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const std::array<int, 3> dims : {std::array<int, 3>{30, 29, 27}, std::array<int, 3>{61, 23, 17}}) {
    Grid g;
    g.dims = dims;
    const int n = g.num_nodes();
    REQUIRE(n > 20000);  // the operator's parallel threshold
    Eigen::VectorXd w = Eigen::VectorXd::Zero(n);
    for (int i = 0; i < 300; ++i) w[rng() % n] = 1e4;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> X(n, 3);
    for (int i = 0; i < X.size(); ++i) X.data()[i] = u(rng);
    const Eigen::MatrixXd expected = normal_matrix(g, w) * Eigen::MatrixXd(X);
    for (int threads : {1, 2, 3, 7, 16, 24}) {
      CAPTURE(dims[2]);
      CAPTURE(threads);
      omp_set_num_threads(threads);
      detail::StencilScratch<double> buffers;
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Y(n, 3);
      detail::normal_operator(g.dims, w.data(), X.data(), Y.data(), false, buffers);
      CHECK((Eigen::MatrixXd(Y) - expected).norm() <= 1e-12 * expected.norm());
      // In place: each line's result overwrites the operand's line as it is handed out.
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Z = X;
      double* z = Z.data();
      detail::normal_operator_visit(g.dims, w.data(), z, buffers,
                                    [&](std::ptrdiff_t f0, std::ptrdiff_t len, const double* v) {
                                      for (std::ptrdiff_t f = 0; f < len; ++f) z[f0 + f] = v[f];
                                    });
      CHECK((Eigen::MatrixXd(Z) - expected).norm() <= 1e-12 * expected.norm());
    }
  }
  omp_set_num_threads(threads_before);
}
