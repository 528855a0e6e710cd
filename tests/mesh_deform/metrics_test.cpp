#include <doctest/doctest.h>

#include "lapis/mesh_deform/metrics.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;

TEST_CASE("mesh_deform: distortion is zero under rigid motion and measures a uniform scale") {
  const TriMesh m = test::box_bar(3, 1.0, 2.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vertices X = (m.V * R.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3);
  const Distortion d = distortion(m, X);
  CHECK(d.edge_length.max < 1e-12);
  CHECK(d.laplacian_length.max < 1e-9);
  CHECK(d.angle.max < 1e-9);
  CHECK(d.arap_energy < 1e-20);
  const Distortion s = distortion(m, 2.0 * m.V);
  CHECK(s.edge_length.mean == doctest::Approx(1.0));
  CHECK(s.laplacian_length.mean == doctest::Approx(1.0));
  CHECK(s.angle.max < 1e-9);
  CHECK(s.arap_energy == doctest::Approx(1.0));  // Σ w ‖2e − e‖² / Σ w ‖e‖², R = I
  CHECK_THROWS_WITH_AS(distortion(m, X.topRows(3)),
                       doctest::Contains("mesh_deform::distortion(): deformed positions have 3 rows"),
                       lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: summaries give mean, max and 95th percentile") {
  std::vector<double> v;
  for (int i = 1; i <= 100; ++i) v.push_back(i);
  const Summary s = summarize(v);
  CHECK(s.mean == doctest::Approx(50.5));
  CHECK(s.max == 100);
  CHECK(s.p95 == 95);
  CHECK(s.count == 100);
  CHECK(summarize({}).count == 0);
}
