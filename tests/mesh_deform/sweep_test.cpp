// The full real-mesh sweep (label `sweep`): every method on every mesh of assets/external.
#include "sweep.h"

using namespace lapis::mesh_deform;

TEST_CASE("mesh_deform sweep: every method on every real mesh") {
  const std::vector<std::string> names = sweep::external_meshes();
  REQUIRE_MESSAGE(!names.empty(), "assets/external has no meshes: run scripts/setup");
  for (const std::string& name : names) {
    const TriMesh m = sweep::load_external(name);
    for (const sweep::MethodCase& method : sweep::methods()) {
      CAPTURE(name);
      CAPTURE(method.name);
      sweep::check_identity(method, m);
      sweep::check_all_handle_motion(method, m);
      sweep::check_bend(method, m, name);
    }
  }
}

// Iteration for iteration on every mesh; converged (thousands of iterations of both) on those
// up to 12K vertices, to keep the sweep within minutes.
TEST_CASE("mesh_deform sweep: ARAP agrees with CGAL's ORIGINAL_ARAP on every real mesh") {
  for (const std::string& name : sweep::external_meshes()) {
    CAPTURE(name);
    const TriMesh m = sweep::load_external(name);
    sweep::check_arap_against_cgal(m, 20, m.num_vertices() <= 12000 ? 0.01 : -1);
  }
}

TEST_CASE("mesh_deform sweep: implicit editing turns real meshes the commanded way over 270 and 360 degrees") {
  for (const std::string name : {"camel", "dino", "armadillo"}) {
    CAPTURE(name);
    const TriMesh m = sweep::load_external(name);
    sweep::check_large_twist(m, 270);
    sweep::check_large_twist(m, 360);
  }
}
