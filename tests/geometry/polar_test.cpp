// 3x3 SVD, polar rotation, nearest similarity, similarity fit and local frames.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/polar.h"

using namespace lapis::geometry;

namespace {
Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

bool is_rotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-13 && std::abs(R.determinant() - 1) < 1e-13;
}

// Random matrices including the hard cases: rank deficient, reflections, repeated and tiny
// singular values.
std::vector<Eigen::Matrix3d> test_matrices() {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Eigen::Matrix3d> out;
  for (int i = 0; i < 2000; ++i) {
    Eigen::Matrix3d M;
    for (int k = 0; k < 9; ++k) M(k / 3, k % 3) = u(rng);
    out.push_back(M);
  }
  const double sv[][3] = {{1, 1, 1},        {1, 1, -1},     {2, 1, 0}, {1, 0, 0},  {0, 0, 0},
                          {1, 1e-9, 1e-12}, {1e8, 1, 1e-8}, {3, 3, 1}, {1, 2, -2}, {5, 1e-300, 0}};
  for (const auto& s : sv)
    for (int rep = 0; rep < 20; ++rep)
      out.push_back(random_rotation(rng) * Eigen::Vector3d(s[0], s[1], s[2]).asDiagonal() * random_rotation(rng));
  out.push_back(Eigen::Matrix3d::Identity());
  out.push_back(-Eigen::Matrix3d::Identity());
  out.push_back(Eigen::Vector3d(1, -1, 1).asDiagonal());
  return out;
}
}  // namespace

TEST_CASE("geometry: svd3 reconstructs A with rotations and ordered signed singular values") {
  for (const Eigen::Matrix3d& A : test_matrices()) {
    Eigen::Matrix3d U, V;
    Eigen::Vector3d S;
    svd3(A, U, S, V);
    CAPTURE(A);
    CHECK(is_rotation(U));
    CHECK(is_rotation(V));
    CHECK((U * S.asDiagonal() * V.transpose() - A).norm() <= 1e-13 * std::max(1.0, A.norm()));
    CHECK(S[0] >= S[1]);
    CHECK(S[1] >= std::abs(S[2]));
    CHECK(S[1] >= 0);
    // Magnitudes agree with Eigen's conventional SVD.
    const Eigen::Vector3d ref = Eigen::JacobiSVD<Eigen::Matrix3d>(A).singularValues();
    CHECK((S.cwiseAbs() - ref).norm() <= 1e-13 * std::max(1.0, ref[0]));
    // The sign of S(2) is the sign of det(A) wherever rounding does not decide it.
    if (std::abs(S[2]) > 1e-10 * S[0]) CHECK((S[2] < 0) == (A.determinant() < 0));
  }
}

TEST_CASE("geometry: polar decomposition returns a proper rotation, the nearest one") {
  std::mt19937 rng(3);
  for (const Eigen::Matrix3d& M : test_matrices()) {
    const Eigen::Matrix3d R = polar_rotation(M);
    CHECK(is_rotation(R));
    // Nearest: no small rotation of R gets closer to M.
    const double d = (M - R).norm();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d Q = Eigen::AngleAxisd(1e-3, random_rotation(rng).col(0)).toRotationMatrix() * R;
      CHECK((M - Q).norm() >= d - 1e-12);
    }
  }
  // A rotation times a symmetric positive definite stretch comes back exactly.
  const Eigen::Matrix3d R0 = random_rotation(rng);
  Eigen::Matrix3d P;
  P << 2, 0.3, 0.1, 0.3, 1.5, -0.2, 0.1, -0.2, 0.7;
  CHECK((polar_rotation(R0 * P) - R0).norm() < 1e-13);
}

TEST_CASE("geometry: nearest similarity removes shear as thesis 2.4.4") {
  std::mt19937 rng(9);
  const Eigen::Matrix3d U = random_rotation(rng), V = random_rotation(rng);
  const Eigen::Matrix3d M = U * Eigen::Vector3d(3, 2, 0.5).asDiagonal() * V.transpose();
  const Similarity3 sim = nearest_similarity(M);
  CHECK((sim.R - U * V.transpose()).norm() < 1e-12);
  CHECK(sim.s == doctest::Approx(std::sqrt((9 + 4 + 0.25) / 3)));
  CHECK(sim.t.isZero());
  const Similarity3 pure = nearest_similarity(2.5 * U);  // a pure similarity is a fixed point
  CHECK((pure.R - U).norm() < 1e-13);
  CHECK(pure.s == doctest::Approx(2.5));
}

TEST_CASE("geometry: the similarity fit recovers a random similarity to 1e-12") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d R = random_rotation(rng);
    const double s = 0.1 + 3 * (u(rng) + 1);
    const Eigen::Vector3d t(u(rng) * 10, u(rng) * 10, u(rng) * 10);
    Eigen::MatrixX3d from(30, 3);
    for (int i = 0; i < from.size(); ++i) from.data()[i] = u(rng);
    const Eigen::MatrixX3d to = ((s * from * R.transpose()).rowwise() + t.transpose());
    const Similarity3 fit = fit_similarity(from, to);
    CHECK((fit.R - R).norm() < 1e-12);
    CHECK(std::abs(fit.s - s) < 1e-12 * s);
    CHECK((fit.t - t).norm() < 1e-12 * (1 + t.norm()));
    const Similarity3 rigid = fit_similarity(from, to, false);
    CHECK(rigid.s == 1.0);
    CHECK((rigid.R - R).norm() < 1e-12);
  }
  // A mirrored point set still gets a proper rotation.
  Eigen::MatrixX3d pts = Eigen::MatrixX3d::Random(10, 3);
  Eigen::MatrixX3d mirrored = pts;
  mirrored.col(0) *= -1;
  CHECK(is_rotation(fit_similarity(pts, mirrored).R));
  CHECK_THROWS_WITH_AS(fit_similarity(pts, pts.topRows(3)),
                       "geometry::fit_similarity(): 10 and 3 points, expected the same number, at least 1",
                       lapis::InvalidArgument);
  CHECK_THROWS_AS(fit_similarity(Eigen::MatrixX3d::Ones(4, 3), pts.topRows(4)), lapis::InvalidArgument);
}

TEST_CASE("geometry: local frames are right-handed orthonormal") {
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  for (int i = 0; i < 1000; ++i) {
    const Eigen::Vector3d n(g(rng), g(rng), i % 100 == 0 ? -1e-20 : g(rng));
    const Eigen::Vector3d ref(g(rng), g(rng), g(rng));
    for (const Eigen::Matrix3d& F : {local_frame(n), local_frame(n, ref)}) {
      CHECK(is_rotation(F));
      CHECK((F.col(2) - n.normalized()).norm() < 1e-14);
    }
    CHECK(local_frame(n, ref).col(0).dot(ref) > 0);
  }
  CHECK(is_rotation(local_frame(Eigen::Vector3d(0, 0, -1))));
  CHECK_THROWS_AS(local_frame(Eigen::Vector3d::Zero()), lapis::InvalidArgument);
}
