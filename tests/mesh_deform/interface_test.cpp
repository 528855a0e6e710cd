// The deformer interface: validation messages, the dirty flag, identity for every method.
#include <doctest/doctest.h>

#include <memory>

#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/naive_laplacian.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;
using lapis::mesh_deform::test::box_bar;

namespace {

std::vector<std::unique_ptr<Deformer>> all_methods(const TriMesh& m) {
  std::vector<std::unique_ptr<Deformer>> d;
  d.push_back(std::make_unique<NaiveLaplacianDeformer>(m));
  d.push_back(std::make_unique<ImplicitLaplacianDeformer>(m));
  ImplicitOptions uni;
  uni.weights = LaplacianWeights::Uniform;
  uni.shearing = ShearingRemoval::ScaleFeatures;
  d.push_back(std::make_unique<ImplicitLaplacianDeformer>(m, uni));
  ImplicitOptions none;
  none.shearing = ShearingRemoval::None;
  d.push_back(std::make_unique<ImplicitLaplacianDeformer>(m, none));
  d.push_back(std::make_unique<ArapDeformer>(m));
  NaiveOptions soft;
  soft.soft_handles = true;
  d.push_back(std::make_unique<NaiveLaplacianDeformer>(m, soft));
  d.push_back(std::make_unique<EdgeLaplacianDeformer>(m));
  EdgeLaplacianOptions vertex_cotan;
  vertex_cotan.domain = LaplacianDomain::Vertices;
  vertex_cotan.weights = LaplacianWeights::Cotangent;
  d.push_back(std::make_unique<EdgeLaplacianDeformer>(m, vertex_cotan));
  return d;
}

std::string message_of(Deformer& d, const Selection& s) {
  d.set_selection(s);
  try {
    d.precompute();
  } catch (const lapis::InvalidArgument& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("mesh_deform: identity handle transforms return the rest mesh for every method") {
  const TriMesh m = box_bar(4, 1.0, 4.0);
  Selection s = test::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  s.point_handles.push_back(test::slab(m, 2, 0.5, 0.55).front());
  for (auto& d : all_methods(m)) {
    CAPTURE(d->name());
    d->set_selection(s);
    const Vertices X = d->deform(HandleTransforms::identity(s));
    CHECK((X - m.V).norm() <= 1e-9 * m.V.norm());
  }
}

TEST_CASE("mesh_deform: invalid selections throw messages naming the cause") {
  const TriMesh m = box_bar(2, 1.0, 2.0);
  const int n = m.num_vertices();
  ImplicitLaplacianDeformer d(m);
  const std::string pre = "mesh_deform::Deformer::precompute(): ";
  CHECK(message_of(d, Selection{}) == pre + "ROI is empty");
  CHECK(message_of(d, Selection{{0, n}, {}, {}}) ==
        pre + "ROI vertex " + std::to_string(n) + " out of range [0, " + std::to_string(n) + ")");
  CHECK(message_of(d, Selection{{0, 1, 1}, {}, {}}) == pre + "ROI vertex 1 listed twice");
  CHECK(message_of(d, Selection{{0, 1}, {{2}}, {}}) == pre + "region handle 0 vertex 2 is outside the ROI");
  CHECK(message_of(d, Selection{{0, 1}, {{}}, {}}) == pre + "region handle 0 is empty");
  CHECK(message_of(d, Selection{{0, 1, 2}, {{0}}, {0}}) ==
        pre + "point handle 0 vertex 0 already belongs to region handle 0");
  CHECK(message_of(d, Selection{{0, 1}, {}, {-1}}) ==
        pre + "point handle 0 vertex -1 out of range [0, " + std::to_string(n) + ")");
  CHECK(message_of(d, Selection{test::all_vertices(m), {}, {}}) ==
        pre + "the ROI covers the whole mesh and there is no handle: nothing anchors the deformation");
  CHECK(message_of(d, Selection{{0, 1}, {{0, 1}}, {}}) ==
        pre + "every ROI vertex is a handle vertex: nothing is left to deform");
}

TEST_CASE("mesh_deform: deform rejects wrong transform counts and non-affine transforms") {
  const TriMesh m = box_bar(2, 1.0, 2.0);
  const Selection s = test::bottom_fixed_top_handle(m, 2, 0.2, 0.2);
  NaiveLaplacianDeformer d(m);
  d.set_selection(s);
  HandleTransforms t;
  CHECK_THROWS_WITH_AS(d.deform(t),
                       "mesh_deform::Deformer::deform(): 0 region and 0 point transforms, expected 1 and 0",
                       lapis::InvalidArgument);
  t = HandleTransforms::identity(s);
  t.regions[0](3, 0) = 1;
  CHECK_THROWS_WITH_AS(
      d.deform(t),
      "mesh_deform::Deformer::deform(): transform of region handle 0 is not affine (bottom row must be 0 0 0 1)",
      lapis::InvalidArgument);
  t.regions[0](3, 0) = 0;
  t.regions[0](0, 3) = std::nan("");
  CHECK_THROWS_WITH_AS(d.deform(t), "mesh_deform::Deformer::deform(): transform of region handle 0 is not finite",
                       lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: bad meshes are rejected at construction") {
  TriMesh m = box_bar(2, 1.0, 2.0);
  m.F(0, 0) = m.num_vertices();
  CHECK_THROWS_AS(NaiveLaplacianDeformer{m}, lapis::InvalidArgument);
  TriMesh e;
  CHECK_THROWS_WITH_AS(NaiveLaplacianDeformer{e}, "mesh_deform::Deformer::Deformer(): mesh has no vertices or no faces",
                       lapis::InvalidArgument);
}

TEST_CASE("mesh_deform: precompute runs once per selection, moving handles never re-runs it") {
  const TriMesh m = box_bar(3, 1.0, 3.0);
  const Selection s = test::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  ArapDeformer d(m);
  d.set_selection(s);
  CHECK(d.dirty());
  HandleTransforms t = HandleTransforms::identity(s);
  d.deform(t);
  CHECK_FALSE(d.dirty());
  const double setup = d.report().setup_ms;
  t.regions[0](0, 3) = 0.3;
  d.deform(t);
  CHECK_FALSE(d.dirty());
  CHECK(d.report().setup_ms == setup);
  d.set_selection(s);
  CHECK(d.dirty());
}

TEST_CASE("mesh_deform: a face collapsed onto its edge neither breaks nor bends any method") {
  const TriMesh bar = box_bar(4, 1.0, 4.0);
  TriMesh m = bar;
  // The first face with every corner mid-bar; its first corner moved onto the opposite edge,
  // 1e-13 of the way back. Its cotangents would be ~1e13: every method's precompute threw
  // "not positive definite" until degenerate faces were dropped (geometry/laplacian.h).
  int f = 0;
  const auto mid_bar = [&](int v) { return m.V(v, 2) > 1.5 && m.V(v, 2) < 2.5; };
  while (!(mid_bar(m.F(f, 0)) && mid_bar(m.F(f, 1)) && mid_bar(m.F(f, 2)))) ++f;
  const int v = m.F(f, 0);
  const Eigen::RowVector3d edge_middle = 0.5 * (m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2)));
  m.V.row(v) = edge_middle + 1e-13 * (m.V.row(v) - edge_middle);
  const Selection s = test::bottom_fixed_top_handle(m, 2, 0.1, 0.1);
  HandleTransforms drag = HandleTransforms::identity(s);
  drag.regions[0](0, 3) = 0.5;  // the top half a unit along x
  auto originals = all_methods(bar);
  auto collapsed = all_methods(m);
  for (size_t k = 0; k < collapsed.size(); ++k) {
    Deformer& d = *collapsed[k];
    CAPTURE(d.name());
    d.set_selection(s);
    CHECK((d.deform(HandleTransforms::identity(s)) - m.V).norm() <= 1e-9 * m.V.norm());
    const Vertices X = d.deform(drag);
    REQUIRE(X.allFinite());
    // Away from the collapsed face the result is the unmodified bar's.
    originals[k]->set_selection(s);
    const Vertices Y = originals[k]->deform(drag);
    double far = 0;
    for (int u = 0; u < m.num_vertices(); ++u)
      if ((bar.V.row(u) - bar.V.row(v)).norm() > 1.0) far = std::max(far, (X.row(u) - Y.row(u)).norm());
    CAPTURE(far);
    CHECK(far < 0.05);  // 0.001-0.01 with the face dropped
  }
}

TEST_CASE("mesh_deform: free vertices with only degenerate faces are named before any solve") {
  const TriMesh bar = box_bar(4, 1.0, 4.0);
  TriMesh m = bar;
  // A band of the bar squeezed onto one point: vertices inside it keep no face with usable
  // angles. The solvers failed on a singular matrix naming no vertex.
  for (int v = 0; v < m.num_vertices(); ++v)
    if (bar.V(v, 2) > 2.0 && bar.V(v, 2) < 3.2) m.V.row(v) << 0.5, 0.5, 2.6;
  const Selection s = test::bottom_fixed_top_handle(bar, 2, 0.1, 0.1);
  // Uniform naive editing measures no angle: the squeezed mesh is still a valid input to it.
  NaiveOptions uniform;
  uniform.weights = LaplacianWeights::Uniform;
  NaiveLaplacianDeformer u(m, uniform);
  u.set_selection(s);
  CHECK((u.deform(HandleTransforms::identity(s)) - m.V).norm() <= 1e-9 * m.V.norm());
  for (auto& d : all_methods(m)) {
    CAPTURE(d->name());
    d->set_selection(s);
    // Nor does the edge-based method with its default uniform weights (rotations and scales
    // are fitted to whatever cells the squeeze left).
    if (const auto* e = dynamic_cast<const EdgeLaplacianDeformer*>(d.get());
        e && e->options().weights == LaplacianWeights::Uniform) {
      CHECK((d->deform(HandleTransforms::identity(s)) - m.V).norm() <= 1e-9 * m.V.norm());
      continue;
    }
    try {
      d->precompute();
      FAIL("no error");
    } catch (const lapis::InvalidArgument& e) {
      const std::string what = e.what();
      CHECK(what.starts_with("mesh_deform::Deformer::precompute(): "));
      CHECK(what.find(" free vertices (the first: ") != std::string::npos);
      CHECK(what.find(") have no face with usable angles") != std::string::npos);
    }
  }
}
