// Merging along an optimal (or the user's) boundary, thesis §3.4.1: "move the boundary vertices
// ∂Ω to their corresponding positions ∂Ω* and deform Ω by the method in Section 2.4".
#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_merge/constraints.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "lapis/mesh_merge/refine.h"
#include "lapis/mesh_merge/zip.h"
#include "optimal_boundary_detail.h"
#include "uv_locator.h"

namespace lapis::mesh_merge {
namespace {

using geometry::Connectivity;

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool inside_polygon(const Eigen::MatrixX2d& polygon, const Eigen::Vector2d& q) {
  bool in = false;
  for (Eigen::Index i = 0, n = polygon.rows(); i < n; ++i) {
    const Eigen::Vector2d a = polygon.row(i), b = polygon.row((i + 1) % n);
    if ((a.y() > q.y()) != (b.y() > q.y()) && q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                    const Eigen::Vector2d& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

std::vector<int> complement(const std::vector<int>& sorted, int n) {
  std::vector<int> out;
  for (int i = 0, k = 0; i < n; ++i) {
    while (k < static_cast<int>(sorted.size()) && sorted[k] < i) ++k;
    if (k == static_cast<int>(sorted.size()) || sorted[k] != i) out.push_back(i);
  }
  return out;
}

}  // namespace

// Ωf's faces and every face reachable from them without crossing the loop.
std::vector<int> BoundaryOptimizer::faces_inside(const std::vector<int>& loop) const {
  const Connectivity conn(source_);
  std::set<int> wall;
  for (size_t i = 0; i < loop.size(); ++i) wall.insert(conn.find_edge(loop[i], loop[(i + 1) % loop.size()]));
  std::vector<char> seen(static_cast<size_t>(source_.num_faces()), 0);
  std::vector<int> pending = feature_faces_, inside;
  for (int f : pending) seen[f] = 1;
  while (!pending.empty()) {
    const int f = pending.back();
    pending.pop_back();
    inside.push_back(f);
    for (int k = 0; k < 3; ++k) {
      const int g = conn.face_neighbor(f, k);
      if (g >= 0 && !seen[g] && !wall.count(conn.face_edge(f, k))) seen[g] = 1, pending.push_back(g);
    }
  }
  std::sort(inside.begin(), inside.end());
  for (int f : inside)
    if (!std::binary_search(band_faces_.begin(), band_faces_.end(), f) &&
        !std::binary_search(feature_faces_.begin(), feature_faces_.end(), f))
      detail::fail_optimal("the boundary does not separate Ωf from the rest of the source (face " + std::to_string(f) +
                           " outside Ω0 is reached)");
  return inside;
}

// Target faces of Ω1 whose uv triangle meets the polygon's inside: a corner inside the polygon,
// a polygon corner inside the triangle, or an edge crossing the polygon's.
std::vector<int> BoundaryOptimizer::faces_under(const Eigen::MatrixX2d& polygon) const {
  const Eigen::Vector2d lo = polygon.colwise().minCoeff(), hi = polygon.colwise().maxCoeff();
  std::vector<int> under;
  for (int f = 0; f < target_region_.num_faces(); ++f) {
    Eigen::Vector2d p[3];
    for (int j = 0; j < 3; ++j) p[j] = target_region_uv_.row(target_region_.F(f, j));
    const Eigen::Vector2d flo = p[0].cwiseMin(p[1]).cwiseMin(p[2]), fhi = p[0].cwiseMax(p[1]).cwiseMax(p[2]);
    if ((flo.array() > hi.array()).any() || (fhi.array() < lo.array()).any()) continue;
    bool meets = inside_polygon(polygon, p[0]) || inside_polygon(polygon, p[1]) || inside_polygon(polygon, p[2]);
    const double area = cross(p[1] - p[0], p[2] - p[0]);
    for (Eigen::Index i = 0, n = polygon.rows(); i < n && !meets; ++i) {
      const Eigen::Vector2d a = polygon.row(i), b = polygon.row((i + 1) % n);
      const double w1 = cross(p[1] - a, p[2] - a) / area, w2 = cross(p[2] - a, p[0] - a) / area;
      meets = (w1 >= 0 && w2 >= 0 && w1 + w2 <= 1);
      for (int j = 0; j < 3 && !meets; ++j) meets = segments_cross(a, b, p[j], p[(j + 1) % 3]);
    }
    if (meets) under.push_back(f);
  }
  return under;
}

bool BoundaryOptimizer::hole_reaches_border(const std::vector<int>& region_faces) const {
  const Connectivity region(target_region_);
  std::vector<char> border(static_cast<size_t>(target_region_.num_vertices()), 0);
  for (const auto& l : region.boundary_loops())
    for (int v : l) border[v] = 1;
  for (int f : region_faces)
    for (int j = 0; j < 3; ++j)
      if (border[target_region_.F(f, j)]) return true;
  return false;
}

Eigen::Vector3d BoundaryOptimizer::point_at(const Eigen::Vector2d& uv) const {
  const detail::UvHit hit = detail::UvLocator(target_region_uv_, target_region_.F).locate(uv);
  const Eigen::Vector3d w = hit.weights.cwiseMax(0.0) / hit.weights.cwiseMax(0.0).sum();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int j = 0; j < 3; ++j) p += w(j) * target_region_.V.row(target_region_.F(hit.face, j)).transpose();
  return p;
}

namespace {

// The part of the source the loop encloses, and for each of its boundary vertices the uv of its
// image: refinement's new vertices take the uv interpolated along their edge of the loop.
struct SourcePart {
  TriMesh mesh;
  std::vector<int> source_of;  // part vertex -> source vertex (-1 for refinement's)
  std::vector<int> loop;       // the part's boundary, the part on its left
  Eigen::MatrixX2d loop_uv;    // parallel to loop
  int refine_levels = 0;
};

SourcePart cut_source_part(const TriMesh& source, const std::vector<int>& inside, const Eigen::MatrixX2d& image_uv,
                           const MergeOptions& options) {
  SourcePart p;
  std::vector<int> part_of;
  p.mesh = geometry::remove_faces(source, complement(inside, source.num_faces()), &part_of);
  const int given = p.mesh.num_vertices();
  p.source_of.assign(static_cast<size_t>(given), -1);
  for (int v = 0; v < source.num_vertices(); ++v)
    if (part_of[v] >= 0) p.source_of[part_of[v]] = v;
  p.refine_levels = refine_short_boundary(p.mesh, options.refine_ratio, options.refine_levels);
  p.source_of.resize(static_cast<size_t>(p.mesh.num_vertices()), -1);
  const Connectivity conn(p.mesh);
  if (conn.boundary_loops().size() != 1)
    detail::fail_optimal("the source part inside the boundary has " + std::to_string(conn.boundary_loops().size()) +
                         " boundary loops, expected one");
  p.loop = conn.boundary_loops()[0];
  std::rotate(p.loop.begin(), std::find_if(p.loop.begin(), p.loop.end(), [&](int v) { return v < given; }),
              p.loop.end());
  const size_t n = p.loop.size();
  p.loop_uv.resize(static_cast<Eigen::Index>(n), 2);
  for (size_t i = 0; i < n;) {
    p.loop_uv.row(static_cast<Eigen::Index>(i)) = image_uv.row(p.source_of[p.loop[i]]);
    size_t j = i + 1;  // the next old vertex (n: the first again)
    while (j < n && p.loop[j] >= given) ++j;
    const Eigen::Vector2d a = image_uv.row(p.source_of[p.loop[i]]), b = image_uv.row(p.source_of[p.loop[j % n]]);
    double total = 0;
    for (size_t k = i; k < j; ++k) total += (p.mesh.V.row(p.loop[(k + 1) % n]) - p.mesh.V.row(p.loop[k])).norm();
    double before = 0;
    for (size_t k = i + 1; k < j; ++k) {
      before += (p.mesh.V.row(p.loop[k]) - p.mesh.V.row(p.loop[k - 1])).norm();
      p.loop_uv.row(static_cast<Eigen::Index>(k)) = ((1 - before / total) * a + before / total * b).transpose();
    }
    i = j;
  }
  return p;
}

// Ωf's vertices in the part, without those on the part's boundary (an optimal loop may run
// along ∂Ωf), which their constraints hold already: §3.5's features do not touch the boundary.
std::vector<int> feature_in_part(const TriMesh& source, const std::vector<int>& feature_faces, const SourcePart& part) {
  std::vector<int> part_of(static_cast<size_t>(source.num_vertices()), -1);
  for (size_t v = 0; v < part.source_of.size(); ++v)
    if (part.source_of[v] >= 0) part_of[part.source_of[v]] = static_cast<int>(v);
  std::vector<char> skip(static_cast<size_t>(part.mesh.num_vertices()), 0);
  for (int v : part.loop) skip[v] = 1;
  std::vector<int> held;
  for (int f : feature_faces)
    for (int j = 0; j < 3; ++j) {
      const int v = part_of[source.F(f, j)];
      if (v >= 0 && !skip[v]) skip[v] = 1, held.push_back(v);
    }
  std::sort(held.begin(), held.end());
  return held;
}

}  // namespace

MergeResult BoundaryOptimizer::merge(const OptimalBoundary& b, const MergeOptions& options,
                                     bool along_user_boundary) const {
  const auto t_total = std::chrono::steady_clock::now();
  auto t0 = t_total;
  const std::vector<int>& loop = along_user_boundary ? b.user_loop : b.loop;
  const geometry::Similarity3 T = along_user_boundary ? b.history.front().transform : b.transform;
  MergeResult r;
  SourcePart part = cut_source_part(source_, faces_inside(loop), b.image_uv, options);
  r.refine_levels = part.refine_levels;

  // Boundary conditions: each boundary vertex onto its image, with T's linear part as gradient.
  std::vector<BoundaryConstraint> cons(part.loop.size());
  for (size_t i = 0; i < part.loop.size(); ++i) {
    const int v = part.loop[i];
    cons[i].vertex = v, cons[i].rotation = T.R, cons[i].scale = T.s;
    const int s = part.source_of[v];  // -1 for refinement's vertices
    cons[i].position = s >= 0 ? Eigen::Vector3d(b.image.row(s).transpose())
                              : point_at(part.loop_uv.row(static_cast<Eigen::Index>(i)).transpose());
  }
  mesh_deform::Selection sel;
  mesh_deform::HandleTransforms tf;
  sel.roi.resize(static_cast<size_t>(part.mesh.num_vertices()));
  for (int v = 0; v < part.mesh.num_vertices(); ++v) sel.roi[v] = v;
  add_region_handles(part.mesh, cons, sel, tf);
  mesh_deform::ImplicitLaplacianDeformer deformer(part.mesh, options.implicit);
  deformer.set_selection(std::move(sel));
  if (options.hold_feature) {
    std::vector<int> held = feature_in_part(source_, feature_faces_, part);
    if (held.size() >= 4) deformer.set_shared_gradients({std::move(held)});  // a gradient needs 4 vertices
  }
  deformer.precompute();
  r.source_boundary = part.loop;
  r.roi_vertices = part.mesh.num_vertices();
  r.timings.setup_ms = ms_since(t0);
  t0 = std::chrono::steady_clock::now();
  r.source_deformed = deformer.deform(tf);
  r.solver = deformer.report();
  r.timings.solve_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  zip_onto_target(r, part.mesh.F, part.loop, part.loop_uv);
  r.source_map.assign(static_cast<size_t>(source_.num_vertices()), -1);
  const int offset = r.mesh.num_vertices() - part.mesh.num_vertices();
  for (int v = 0; v < part.mesh.num_vertices(); ++v)
    if (part.source_of[v] >= 0) r.source_map[part.source_of[v]] = v + offset;
  r.source_rest = std::move(part.mesh);
  r.timings.zip_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  if (options.smooth_iterations > 0) {
    // The band's smoothing stops at Ωf, which the user marked to keep as it is: an optimal
    // boundary runs close to it, and the umbrella operator would flatten the feature's foot.
    std::vector<char> in_feature(static_cast<size_t>(r.mesh.num_vertices()), 0);
    for (int f : feature_faces_)
      for (int j = 0; j < 3; ++j) in_feature[r.source_map[source_.F(f, j)]] = 1;
    r.smoothed = seam_band(r.mesh, r.seam_vertices, options.smooth_rings);
    std::erase_if(r.smoothed, [&](int v) { return in_feature[v] != 0; });
    umbrella_smooth(r.mesh, r.smoothed, options.smooth_iterations, options.smooth_lambda);
    // A fold the band cannot undo may move Ωf's vertices next to the seam: a fold is worse
    // than a feature's foot smoothed where it touches the strip.
    if (unfold_seam(r.mesh, r.strip_faces, r.smoothed) > 0)
      unfold_seam(r.mesh, r.strip_faces, seam_band(r.mesh, r.seam_vertices, options.smooth_rings));
  }
  r.timings.smooth_ms = ms_since(t0);
  r.timings.total_ms = ms_since(t_total);
  return r;
}

// The target without the Ω1 faces under the loop's image, then the deformed part appended and
// the gap between its loop and the hole's rim bridged.
void BoundaryOptimizer::zip_onto_target(MergeResult& r, const Faces& part_faces, const std::vector<int>& part_loop,
                                        const Eigen::MatrixX2d& loop_uv) const {
  std::vector<int> removed;
  for (int f : faces_under(loop_uv)) removed.push_back(target_faces_[f]);
  if (removed.empty()) detail::fail_optimal("the boundary's image covers no face of Ω1");
  std::vector<char> touched(static_cast<size_t>(target_.num_vertices()), 0);
  for (int f : removed)
    for (int j = 0; j < 3; ++j) touched[target_.F(f, j)] = 1;
  const TriMesh cut = geometry::remove_faces(target_, removed, &r.target_map);
  std::vector<char> on_region_border(static_cast<size_t>(target_.num_vertices()), 0);
  const Connectivity region(target_region_);
  for (const auto& l : region.boundary_loops())
    for (int v : l) on_region_border[target_vertex_[v]] = 1;
  const Connectivity cc(cut);
  std::vector<int> new_of(static_cast<size_t>(cut.num_vertices()), -1);
  for (int v = 0; v < target_.num_vertices(); ++v)
    if (r.target_map[v] >= 0) new_of[r.target_map[v]] = v;
  std::vector<const std::vector<int>*> rims;
  for (const auto& l : cc.boundary_loops()) {
    bool rim = false, border = false;
    for (int v : l) rim |= touched[new_of[v]] != 0, border |= on_region_border[new_of[v]] != 0;
    if (rim && border)
      detail::fail_optimal("the boundary's image comes within one triangle of Ω1's border; move or shrink the band");
    if (rim) rims.push_back(&l);
  }
  if (rims.size() != 1)
    detail::fail_optimal("the Ω1 faces under the boundary's image are not one disk (" + std::to_string(rims.size()) +
                         " rims)");
  r.mesh.V.resize(cut.num_vertices() + r.source_deformed.rows(), 3);
  r.mesh.V << cut.V, r.source_deformed;
  r.mesh.F.resize(cut.num_faces() + part_faces.rows(), 3);
  r.mesh.F << cut.F, (part_faces.array() + cut.num_vertices()).matrix();
  std::vector<int> a;
  for (int v : part_loop) a.push_back(v + cut.num_vertices());
  const std::vector<int> rim(rims[0]->rbegin(), rims[0]->rend());  // against the target, like a
  const int first = r.mesh.num_faces();
  const int added = geometry::bridge_polylines(r.mesh, a, rim, true);
  for (int f = first; f < first + added; ++f) r.strip_faces.push_back(f);
  r.seam_vertices = a;
  r.seam_vertices.insert(r.seam_vertices.end(), rim.begin(), rim.end());
  std::sort(r.seam_vertices.begin(), r.seam_vertices.end());
}

}  // namespace lapis::mesh_merge
