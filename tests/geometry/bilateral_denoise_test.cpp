// Bilateral mesh denoising (Fleishman et al. 2003): a flat plane stays put, noise is removed
// where the underlying surface is smooth, the filter commutes with similarities, and bad
// options are typed errors.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "lapis/core/error.h"
#include "lapis/geometry/bilateral_denoise.h"
#include "lapis/geometry/procedural.h"

using namespace lapis;
using namespace lapis::geometry;

namespace {

// Each vertex moved along `direction(v)` by uniform noise in [-amplitude, amplitude].
template <class Direction>
TriMesh with_noise(TriMesh m, double amplitude, Direction direction) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (int v = 0; v < m.num_vertices(); ++v) m.V.row(v) += u(rng) * direction(v);
  return m;
}

double rms(const Eigen::VectorXd& x) { return std::sqrt(x.squaredNorm() / static_cast<double>(x.size())); }

// The spread of the distances from the centre: the noise on a sphere, apart from the uniform
// shrinking every smoothing of a curved surface brings (each neighbourhood lies below the
// tangent plane).
double radial_spread(const TriMesh& m) {
  const Eigen::VectorXd r = m.V.rowwise().norm();
  return rms(r.array() - r.mean());
}

}  // namespace

TEST_CASE("geometry: bilateral denoising leaves a plane where it is") {
  const TriMesh plane = make_plane_grid(30, 20, 2.0, 1.0);
  const TriMesh out = bilateral_denoise(plane, {3, 0});
  CHECK((out.V - plane.V).cwiseAbs().maxCoeff() == 0);
  CHECK(out.F == plane.F);
}

TEST_CASE("geometry: bilateral denoising removes noise from a plane and a sphere") {
  const TriMesh plane = make_plane_grid(40, 40);
  const TriMesh noisy = with_noise(plane, 0.2 / 39, [](int) { return Eigen::RowVector3d(0, 0, 1); });
  const TriMesh clean = bilateral_denoise(noisy, {3, 0});
  MESSAGE("plane: rms height " << rms(noisy.V.col(2)) << " -> " << rms(clean.V.col(2)));
  CHECK(rms(clean.V.col(2)) < 0.5 * rms(noisy.V.col(2)));

  const TriMesh sphere = make_icosphere(4);
  const TriMesh rough = with_noise(sphere, 0.004, [&](int v) { return sphere.V.row(v).normalized(); });
  const TriMesh smooth = bilateral_denoise(rough, {2, 0});
  MESSAGE("sphere: radial spread " << radial_spread(rough) << " -> " << radial_spread(smooth) << ", mean radius "
                                   << smooth.V.rowwise().norm().mean());
  CHECK(radial_spread(smooth) < 0.5 * radial_spread(rough));
  CHECK(smooth.V.rowwise().norm().mean() > 0.99);
}

TEST_CASE("geometry: bilateral denoising commutes with a similarity") {
  const TriMesh sphere = make_icosphere(3);
  const TriMesh rough = with_noise(sphere, 0.01, [&](int v) { return sphere.V.row(v).normalized(); });
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const double s = 3.5;
  const Eigen::RowVector3d t(0.3, -2, 5);
  TriMesh moved = rough;
  moved.V = (s * rough.V * R.transpose()).rowwise() + t;
  const Vertices expected = (s * bilateral_denoise(rough, {2, 0}).V * R.transpose()).rowwise() + t;
  CHECK((bilateral_denoise(moved, {2, 0}).V - expected).cwiseAbs().maxCoeff() < 1e-12 * s * 10);
  CHECK((bilateral_denoise(rough, {0, 0}).V - rough.V).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("geometry: bilateral denoising rejects bad options") {
  const TriMesh m = make_icosphere(1);
  CHECK_THROWS_AS(bilateral_denoise(m, {-1, 0}), InvalidArgument);
  CHECK_THROWS_AS(bilateral_denoise(m, {1, -0.1}), InvalidArgument);
  CHECK_THROWS_AS(bilateral_denoise(m, {1, std::nan("")}), InvalidArgument);
  CHECK_THROWS_AS(bilateral_denoise(m, {1, 1e308 * 10}), InvalidArgument);
}
