// The multigrid's matrix-free transfers (grid_transfer.h) against the trilinear prolongation
// assembled as a matrix, with zero rows at pinned fine nodes, on grids of even and odd sizes.
#include <doctest/doctest.h>

#include <Eigen/SparseCore>
#include <random>
#include <vector>

#include "grid_transfer.h"

using namespace lapis::hair_field::detail;

namespace {

// P (fine × coarse) from the 1D rule, zero rows at pinned nodes.
Eigen::SparseMatrix<double, Eigen::RowMajor> prolongation_matrix(const std::array<int, 3>& fd,
                                                                 const std::array<int, 3>& cd,
                                                                 const std::vector<char>& pinned) {
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < fd[2]; ++k)
    for (int j = 0; j < fd[1]; ++j)
      for (int i = 0; i < fd[0]; ++i) {
        const int row = i + fd[0] * (j + fd[1] * k);
        if (pinned[row]) continue;
        const CoarseNeighbours nx = coarse_neighbours(i), ny = coarse_neighbours(j), nz = coarse_neighbours(k);
        for (int c = 0; c < nz.count; ++c)
          for (int b = 0; b < ny.count; ++b)
            for (int a = 0; a < nx.count; ++a)
              t.emplace_back(row, (nx.first + a) + cd[0] * ((ny.first + b) + cd[1] * (nz.first + c)),
                             double(nx.weight) * ny.weight * nz.weight);
      }
  Eigen::SparseMatrix<double, Eigen::RowMajor> P(fd[0] * fd[1] * fd[2], cd[0] * cd[1] * cd[2]);
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace

TEST_CASE("hair_field: matrix-free multigrid transfers equal the prolongation matrix and its transpose") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (const std::array<int, 3> fd : {std::array<int, 3>{9, 8, 7}, std::array<int, 3>{40, 13, 30}}) {
    const std::array<int, 3> cd{fd[0] / 2 + 1, fd[1] / 2 + 1, fd[2] / 2 + 1};
    const int nf = fd[0] * fd[1] * fd[2], nc = cd[0] * cd[1] * cd[2];
    std::vector<char> pinned(nf, 0);
    for (int i = 0; i < nf / 10; ++i) pinned[rng() % nf] = 1;
    const auto P = prolongation_matrix(fd, cd, pinned);
    CAPTURE(fd[0]);

    // Prolongation adds P xc to what is there.
    Eigen::MatrixXd xc(nc, 3), xf(nf, 3);
    for (int i = 0; i < xc.size(); ++i) xc.data()[i] = u(rng);
    for (int i = 0; i < xf.size(); ++i) xf.data()[i] = u(rng);
    const Eigen::MatrixXd expected_f = xf + P * xc;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> xc_rows = xc, xf_rows = xf;
    prolong_add(fd, cd, pinned.data(), xc_rows.data(), xf_rows.data());
    CHECK((Eigen::MatrixXd(xf_rows) - expected_f).norm() <= 1e-13 * expected_f.norm());

    // Restriction is Pᵀ of a residual that is zero at the pinned nodes.
    Eigen::MatrixXd rf(nf, 3);
    for (int i = 0; i < rf.size(); ++i) rf.data()[i] = u(rng);
    for (int i = 0; i < nf; ++i)
      if (pinned[i]) rf.row(i).setZero();
    const Eigen::MatrixXd expected_c = P.transpose() * rf;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> rf_rows = rf, bc_rows(nc, 3);
    restrict_to_coarse(fd, cd, rf_rows.data(), bc_rows.data());
    CHECK((Eigen::MatrixXd(bc_rows) - expected_c).norm() <= 1e-13 * expected_c.norm());
  }
}
