// Deformation transfer by handle correspondence (Au et al. 2007, §6): the identity and rigid
// motions carry over exactly, translation of the source only moves the result, a mesh
// transferred onto itself keeps its deformation up to Eq. 11's residual, a Loop-subdivided
// target follows closely, and mismatched handles are a typed error.
#include <doctest/doctest.h>

#include "lapis/geometry/polar.h"
#include "lapis/geometry/procedural.h"
#include "lapis/mesh_deform/deformation_transfer.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "test_meshes.h"

using namespace lapis::mesh_deform;
namespace t = lapis::mesh_deform::test;
using lapis::geometry::Vertices;

namespace {

Selection bar_selection(const TriMesh& m) { return t::bottom_fixed_top_handle(m, 2, 0.1, 0.1); }

// The bar bent 60° at its handle by the isolines deformer: a source pose.
Vertices bent_bar(const TriMesh& m) {
  IsolinesDeformer d(m);
  d.set_selection(bar_selection(m));
  HandleTransforms h = HandleTransforms::identity(bar_selection(m));
  h.regions[0] = t::rotation_about(Eigen::Vector3d::UnitY(), 60, Eigen::Vector3d(0.5, 0.5, 0.4));
  return d.deform(h);
}

double mean_distance(const Vertices& A, const Vertices& B) { return (A - B).rowwise().norm().mean(); }

}  // namespace

TEST_CASE("transfer: the identity gives the target's rest, a rigid motion that motion, a translation only moves it") {
  const TriMesh src = t::box_bar(6, 1.0, 4.0);
  const TriMesh tgt = t::box_bar(5, 1.2, 3.0);  // another resolution and shape
  DeformationTransfer x(src, bar_selection(src), tgt, bar_selection(tgt));
  const double diag = t::bbox_diagonal(tgt.V);
  CHECK((x.transfer(src.V) - tgt.V).cwiseAbs().maxCoeff() < 1e-9 * diag);
  CHECK(x.report().eq11_residual < 1e-12);
  CHECK(x.report().pinned.size() == 1);

  const Eigen::Matrix4d T = t::rotation_about(Eigen::Vector3d(1, 1, 0), 50, Eigen::Vector3d(0.2, 0.1, 0));
  Vertices moved(src.V.rows(), 3);
  for (int v = 0; v < src.num_vertices(); ++v) moved.row(v) = apply(T, src.V.row(v).transpose()).transpose();
  const Vertices out = x.transfer(moved);
  const auto fit = lapis::geometry::fit_similarity(tgt.V, out, false);
  double rigid_error = 0;
  for (int v = 0; v < tgt.num_vertices(); ++v)
    rigid_error = std::max(rigid_error, (fit(tgt.V.row(v).transpose()) - out.row(v).transpose()).norm());
  CHECK(rigid_error < 1e-8 * diag);
  CHECK((fit.R - T.topLeftCorner<3, 3>()).norm() < 1e-8);

  const Vertices bent = bent_bar(src), shifted = bent.rowwise() + Eigen::RowVector3d(3, -1, 2);
  const Vertices a = x.transfer(bent), b = x.transfer(shifted);
  CHECK(((b - a).rowwise() - Eigen::RowVector3d(3, -1, 2)).cwiseAbs().maxCoeff() < 1e-9 * diag);
}

TEST_CASE("transfer: the rest pose comes back to rounding on a coarse target whose isolines few edges reach") {
  // One quad across: the isolines' edges nearly span a plane, and the ridge of Eq. 11 makes its
  // system ill-conditioned; the rest must still come back exactly, not to 1e-6.
  const TriMesh src = lapis::geometry::make_box_bar(6, 1, 1, 4.0, 1.0, 1.0);
  const TriMesh tgt = lapis::geometry::make_box_bar(5, 1, 1, 4.0, 1.0, 1.0);
  auto select = [](const TriMesh& m) {
    Selection sel;
    for (int v = 0; v < m.num_vertices(); ++v) {
      if (m.V(v, 0) > 0.5) sel.roi.push_back(v);
      if (m.V(v, 0) > 3.75) sel.region_handles.resize(1), sel.region_handles[0].push_back(v);
    }
    return sel;
  };
  DeformationTransfer x(src, select(src), tgt, select(tgt));
  CHECK((x.transfer(src.V) - tgt.V).cwiseAbs().maxCoeff() < 1e-12 * t::bbox_diagonal(tgt.V));
  CHECK(x.report().eq12_residual < 1e-12);
}

TEST_CASE("transfer: onto itself a bend comes back within Eq. 11's residual, onto its Loop subdivision close") {
  const TriMesh src = t::box_bar(6, 1.0, 4.0);
  const Vertices bent = bent_bar(src);
  const double diag = t::bbox_diagonal(src.V);
  DeformationTransfer self(src, bar_selection(src), src, bar_selection(src));
  const Vertices back = self.transfer(bent);
  const double residual = self.report().eq11_residual;
  CHECK(residual > 0);
  CHECK(residual < 0.15);  // per-isoline linear maps of the edges: ~0.09 on this bend
  CHECK(mean_distance(back, bent) < residual * diag);

  const TriMesh fine = lapis::geometry::loop_subdivide(src, 1);  // keeps the first vertices' indices
  Selection fine_sel = bar_selection(src);
  fine_sel.roi = t::slab(fine, 2, 0.1 + 1e-9, 1.0);
  fine_sel.region_handles = {t::slab(fine, 2, 0.9, 1.0)};
  DeformationTransfer onto_fine(src, bar_selection(src), fine, fine_sel);
  const Vertices out = onto_fine.transfer(bent);
  CHECK(mean_distance(out.topRows(src.num_vertices()), bent) < 0.02 * diag);
}

TEST_CASE("transfer: handles that do not correspond one to one are a typed error naming the counts") {
  const TriMesh src = t::box_bar(4, 1.0, 4.0);
  Selection two = bar_selection(src);
  two.region_handles.push_back(t::slab(src, 2, 0.5, 0.55));
  CHECK_THROWS_WITH_AS(DeformationTransfer(src, bar_selection(src), src, two),
                       doctest::Contains("the source has 1 region and 0 point handles and a fixed region, the target 2 "
                                         "region and 0 point handles"),
                       lapis::InvalidArgument);
  Selection whole = t::whole_bar_two_ends(src);
  whole.region_handles.pop_back();
  whole.point_handles = {t::slab(src, 2, 0.95, 1.0).front()};
  CHECK_THROWS_WITH_AS(DeformationTransfer(src, t::whole_bar_two_ends(src), src, whole),
                       doctest::Contains("do not correspond"), lapis::InvalidArgument);
  DeformationTransfer x(src, bar_selection(src), src, bar_selection(src));
  CHECK_THROWS_WITH_AS(x.transfer(src.V.topRows(5)), doctest::Contains("finite positions, got 5 rows"),
                       lapis::InvalidArgument);
}
