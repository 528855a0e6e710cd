// Writes the optimal-boundary example (assets/merge/bump.obj, plate.obj, bump_regions.json): the
// optimal-boundary tests' bump with ripples beyond its flat ring, at a size for a quick demo, and
// a plane to merge it onto. Run from the repository root: build/assets/lapis_make_bump.
#include "lapis/geometry/io.h"
#include "lapis/mesh_merge/regions_file.h"
#include "optimal_fixtures.h"

int main() {
  using namespace lapis::mesh_merge;
  const lapis::geometry::TriMesh source = test::bump_with_ripples(24), target = test::flat_target(30);
  BoundaryRegions regions = test::bump_regions(source);
  regions.target_faces.clear();  // the whole plate
  lapis::geometry::write_mesh("assets/merge/bump.obj", source);
  lapis::geometry::write_mesh("assets/merge/plate.obj", target);
  write_regions_file("assets/merge/bump_regions.json", regions);
  return 0;
}
