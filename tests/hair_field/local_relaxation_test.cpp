// The multigrid solver's local relaxation (local_relaxation.h) against the assembled normal
// matrix: a single node update is that row's exact minimizer, in the interior (the L²/36
// stencil) and at the faces, edges and corners of the box (D itself); sweeps never raise
// the energy, write nothing outside their nodes and converge to the local problem.
#include <doctest/doctest.h>

#include <random>

#include "lapis/hair_field/grid_operators.h"
#include "local_relaxation.h"

using namespace lapis::hair_field;

namespace {

struct Problem {
  Grid g;
  Eigen::VectorXd w;
  Field c, x;
  SparseMatrix A;
};

Problem random_problem(unsigned seed) {
  Problem p;
  p.g.dims = {9, 11, 10};
  p.g.spacing = 1;
  const int n = p.g.num_nodes();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  p.w = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n / 10; ++i) p.w[rng() % n] = 1e4;
  p.c = Field::Zero(n, 3);
  p.x = Field(n, 3);
  for (int i = 0; i < n; ++i) {
    if (p.w[i] != 0) p.c.row(i) = Eigen::RowVector3d(u(rng), u(rng), u(rng));
    p.x.row(i) = Eigen::RowVector3d(u(rng), u(rng), u(rng));
  }
  p.A = normal_matrix(p.g, p.w);
  return p;
}

// E(x) = ½ xᵀAx − bᵀx summed over the three columns, b = w ∘ c.
double energy(const Problem& p, const Field& x) {
  const Eigen::MatrixXd X(x);
  const Eigen::MatrixXd B = p.w.asDiagonal() * Eigen::MatrixXd(p.c);
  return 0.5 * (X.transpose() * (p.A * X)).trace() - (B.transpose() * X).trace();
}

}  // namespace

TEST_CASE("hair_field: local relaxation's node update is the assembled row's minimizer, anywhere in the box") {
  Problem p = random_problem(3);
  const auto& d = p.g.dims;
  // Interior (two or more from every face), one from a face, on a face, an edge, a corner,
  // and constrained nodes among them.
  const std::vector<int> nodes{p.g.index(4, 5, 5), p.g.index(1, 5, 5), p.g.index(4, 0, 5),
                               p.g.index(0, 0, 5), p.g.index(0, 0, 0), p.g.index(d[0] - 1, d[1] - 2, d[2] - 1),
                               p.g.index(2, 2, 2), p.g.index(6, 8, 7)};
  p.w[nodes[1]] = 1e4;  // a constrained node in the general path
  p.w[nodes[6]] = 1e4;  // ... and in the interior path
  p.c.row(nodes[1]) = Eigen::RowVector3d(0.3, -0.2, 0.9);
  p.c.row(nodes[6]) = Eigen::RowVector3d(-0.5, 0.1, 0.4);
  p.A = normal_matrix(p.g, p.w);
  for (int v : nodes) {
    CAPTURE(v);
    Field x = p.x;
    const std::vector<int> one{v};
    detail::gauss_seidel(d, p.w.data(), p.c.data(), one, 1, x.data());
    for (int k = 0; k < 3; ++k) {
      double off = 0, diag = 0;
      for (SparseMatrix::InnerIterator it(p.A, v); it; ++it)
        if (it.row() == v)
          diag = it.value();
        else
          off += it.value() * p.x(it.row(), k);
      const double expected = (p.w[v] * p.c(v, k) - off) / diag;
      CHECK(x(v, k) == doctest::Approx(expected).epsilon(1e-12));
    }
    // Nothing else is written.
    x.row(v) = p.x.row(v);
    CHECK((x - p.x).norm() == 0.0);
  }
}

TEST_CASE("hair_field: local relaxation lowers the energy, stays inside its nodes and solves the local problem") {
  Problem p = random_problem(5);
  const auto& d = p.g.dims;
  std::vector<char> mark(static_cast<size_t>(p.g.num_nodes()), 0);
  const std::vector<int> seeds{p.g.index(3, 4, 4), p.g.index(4, 4, 4), p.g.index(0, 10, 9)};
  const std::vector<int> nodes = detail::nodes_near(d, seeds, 2, mark);
  // The boxes of radius 2: 6×5×5 around the two neighbouring seeds, 3×3×3 in the corner.
  CHECK(nodes.size() == 6 * 5 * 5 + 3 * 3 * 3);
  CHECK(std::is_sorted(nodes.begin(), nodes.end()));
  CHECK(std::count(mark.begin(), mark.end(), 1) == 0);

  std::vector<char> inside(mark.size(), 0);
  for (int v : nodes) inside[v] = 1;
  Field x = p.x;
  double e = energy(p, x);
  for (int sweep = 0; sweep < 20; ++sweep) {
    detail::gauss_seidel(d, p.w.data(), p.c.data(), nodes, 1, x.data());
    const double e_next = energy(p, x);
    CHECK(e_next <= e + 1e-9 * std::abs(e));
    e = e_next;
  }
  for (int i = 0; i < p.g.num_nodes(); ++i)
    if (!inside[i]) CHECK(x.row(i) == p.x.row(i));
  // Many sweeps: the residual on the relaxed nodes (the others held fixed) vanishes.
  const Eigen::MatrixXd B = p.w.asDiagonal() * Eigen::MatrixXd(p.c);
  auto local_residual = [&](const Field& y) {
    const Eigen::MatrixXd R = B - p.A * Eigen::MatrixXd(y);
    double s = 0;
    for (int v : nodes) s += R.row(v).squaredNorm();
    return std::sqrt(s);
  };
  const double r0 = local_residual(p.x);
  detail::gauss_seidel(d, p.w.data(), p.c.data(), nodes, 3000, x.data());
  CHECK(local_residual(x) <= 1e-8 * r0);
}
