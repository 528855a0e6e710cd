#include "lapis/mesh_deform/deformer.h"

#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/geometry/laplacian.h"

namespace lapis::mesh_deform {
namespace {

std::string str(long v) { return std::to_string(v); }

[[noreturn]] void fail(const char* context, const std::string& what) {
  throw InvalidArgument(std::string(context) + ": " + what);
}

void check_index(int v, int n, const char* context, const std::string& where) {
  if (v < 0 || v >= n) fail(context, where + " vertex " + str(v) + " out of range [0, " + str(n) + ")");
}

// Every free vertex needs one face with usable angles: with only degenerate faces (or none)
// it has no cotangent weight, normal or area, and the solvers would fail on a singular
// matrix with nothing to say about which vertex. O(#F), next to a factorization.
void require_shaped_free_vertices(const TriMesh& m, const Layout& L, const char* context) {
  std::vector<char> shaped(static_cast<size_t>(m.num_vertices()), 0);
  for (int f = 0; f < m.num_faces(); ++f)
    if (!geometry::is_thin_triangle(m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2)),
                                    geometry::kDegenerateTriangleHeight))
      for (int k = 0; k < 3; ++k) shaped[static_cast<size_t>(m.F(f, k))] = 1;
  int count = 0, first = -1;
  for (int v : L.free)
    if (!shaped[static_cast<size_t>(v)]) count++, first = first < 0 ? v : first;
  if (count == 0) return;
  const std::string who = count == 1 ? "free vertex " + str(first) + " has"
                                     : str(count) + " free vertices (the first: " + str(first) + ") have";
  fail(context, who + " no face with usable angles: every face around " + (count == 1 ? "it" : "them") +
                    " is degenerate (thinner than 1e-6 of its longest edge) or there is none");
}

}  // namespace

HandleTransforms HandleTransforms::identity(const Selection& s) {
  HandleTransforms t;
  t.regions.assign(s.region_handles.size(), Eigen::Matrix4d::Identity());
  t.points.assign(s.point_handles.size(), Eigen::Vector3d::Zero());
  return t;
}

Layout make_layout(const Selection& s, int n, const char* context) {
  if (s.roi.empty()) fail(context, "ROI is empty");
  Layout L;
  L.role.assign(static_cast<size_t>(n), VertexRole::Fixed);
  L.handle_of.assign(static_cast<size_t>(n), -1);
  for (int v : s.roi) {
    check_index(v, n, context, "ROI");
    if (L.role[v] == VertexRole::Free) fail(context, "ROI vertex " + str(v) + " listed twice");
    L.role[v] = VertexRole::Free;
  }
  auto claim = [&](int v, VertexRole r, int h, const std::string& what) {
    check_index(v, n, context, what);
    if (L.role[v] == VertexRole::Fixed) fail(context, what + " vertex " + str(v) + " is outside the ROI");
    if (L.role[v] != VertexRole::Free)
      fail(context, what + " vertex " + str(v) + " already belongs to " +
                        (L.role[v] == VertexRole::RegionHandle ? "region handle " : "point handle ") +
                        str(L.handle_of[v]));
    L.role[v] = r;
    L.handle_of[v] = h;
  };
  for (size_t h = 0; h < s.region_handles.size(); ++h) {
    if (s.region_handles[h].empty()) fail(context, "region handle " + str(long(h)) + " is empty");
    for (int v : s.region_handles[h]) claim(v, VertexRole::RegionHandle, int(h), "region handle " + str(long(h)));
  }
  for (size_t h = 0; h < s.point_handles.size(); ++h)
    claim(s.point_handles[h], VertexRole::PointHandle, int(h), "point handle " + str(long(h)));
  L.num_region_handles = int(s.region_handles.size());
  L.num_point_handles = int(s.point_handles.size());
  for (int v = 0; v < n; ++v) (L.role[v] == VertexRole::Free ? L.free : L.constrained).push_back(v);
  if (L.constrained.empty())
    fail(context, "the ROI covers the whole mesh and there is no handle: nothing anchors the deformation");
  if (L.free.empty()) fail(context, "every ROI vertex is a handle vertex: nothing is left to deform");
  return L;
}

Deformer::Deformer(TriMesh mesh) : mesh_(std::move(mesh)) {
  constexpr const char* fn = "mesh_deform::Deformer::Deformer()";
  if (mesh_.num_vertices() == 0 || mesh_.num_faces() == 0) fail(fn, "mesh has no vertices or no faces");
  geometry::require_indices_in_range(mesh_, fn);
  if (!mesh_.V.allFinite()) fail(fn, "mesh has a non-finite vertex position");
}

Deformer::~Deformer() = default;

void Deformer::set_selection(Selection selection) {
  selection_ = std::move(selection);
  dirty_ = true;
}

void Deformer::precompute() {
  constexpr const char* fn = "mesh_deform::Deformer::precompute()";
  layout_ = make_layout(selection_, mesh_.num_vertices(), fn);
  dirty_ = true;  // stays dirty if setup throws
  if (needs_face_shapes()) require_shaped_free_vertices(mesh_, layout_, fn);
  setup(layout_);
  dirty_ = false;
}

Vertices Deformer::deform(const HandleTransforms& t) {
  constexpr const char* fn = "mesh_deform::Deformer::deform()";
  if (dirty_) precompute();
  if (t.regions.size() != selection_.region_handles.size() || t.points.size() != selection_.point_handles.size())
    fail(fn, str(long(t.regions.size())) + " region and " + str(long(t.points.size())) +
                 " point transforms, expected " + str(long(selection_.region_handles.size())) + " and " +
                 str(long(selection_.point_handles.size())));
  for (size_t h = 0; h < t.regions.size(); ++h) {
    const Eigen::Matrix4d& T = t.regions[h];
    if (!T.allFinite()) fail(fn, "transform of region handle " + str(long(h)) + " is not finite");
    if (T.bottomRows<1>() != Eigen::RowVector4d(0, 0, 0, 1))
      fail(fn, "transform of region handle " + str(long(h)) + " is not affine (bottom row must be 0 0 0 1)");
  }
  for (size_t h = 0; h < t.points.size(); ++h)
    if (!t.points[h].allFinite()) fail(fn, "translation of point handle " + str(long(h)) + " is not finite");

  Vertices targets = mesh_.V;
  for (int v : layout_.constrained) {
    const int h = layout_.handle_of[v];
    if (layout_.role[v] == VertexRole::RegionHandle)
      targets.row(v) = apply(t.regions[h], mesh_.V.row(v).transpose()).transpose();
    else if (layout_.role[v] == VertexRole::PointHandle)
      targets.row(v) += t.points[h].transpose();
  }
  Vertices out = targets;
  solve(t, targets, out);
  return out;
}

}  // namespace lapis::mesh_deform
