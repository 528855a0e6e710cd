#include <doctest/doctest.h>

#include <filesystem>

#include "lapis/geometry/io.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/cgal_enclosure.h"
#include "lapis/mesh_deform/salient_deformer.h"
#include "lapis/mesh_deform/solid_subspace.h"
#include "test_meshes.h"

using namespace lapis;
using namespace lapis::mesh_deform;

TEST_CASE("mesh_deform: the CGAL enclosure holds the camel near the requested size and serves as the subspace") {
  const TriMesh camel =
      geometry::read_mesh(std::filesystem::path(LAPIS_SOURCE_DIR) / "assets" / "external" / "camel.off");
  EnclosureReport report;
  const geometry::TetMesh tets = cgal_enclosure(camel, EnclosureOptions{}, &report);
  CHECK_NOTHROW(geometry::require_valid_tets(tets, "test"));
  CHECK(tets.num_vertices() >= 50);
  CHECK(tets.num_vertices() <= 200);
  CHECK(report.wrap_vertices > 0);
  const SubspaceEmbedding e = embed_in_subspace(tets, camel.V);
  CHECK(e.strays == 0);
  // As the salient method's subspace: identity handles give the rest mesh.
  SalientOptions o;
  o.detect_features = false;
  SalientDeformer d(camel, o);
  d.set_subspace(tets);
  d.set_selection(test::bottom_fixed_top_handle(camel, 1, 0.1, 0.1));
  const Vertices X = d.deform(HandleTransforms::identity(d.selection()));
  CHECK((X - camel.V).cwiseAbs().maxCoeff() < 1e-10 * test::bbox_diagonal(camel.V));
  CHECK(d.report().subspace_vertices == tets.num_vertices());
}

TEST_CASE("mesh_deform: what CGAL cannot enclose is a typed error naming the stage") {
  // A flat sheet wrapped tightly is a shell thinner than any tetrahedron of an 8-vertex mesh.
  EnclosureOptions coarse;
  coarse.target_vertices = 8;
  coarse.offset_fraction = 0.001;
  CHECK_THROWS_WITH_AS(cgal_enclosure(geometry::make_plane_grid(10, 10), coarse),
                       doctest::Contains("tetrahedral meshing of the wrap produced no tetrahedra"), SolverFailure);
  EnclosureOptions bad;
  bad.offset_fraction = 0;
  CHECK_THROWS_WITH_AS(cgal_enclosure(geometry::make_icosphere(2), bad), doctest::Contains("offset_fraction > 0"),
                       InvalidArgument);
}
