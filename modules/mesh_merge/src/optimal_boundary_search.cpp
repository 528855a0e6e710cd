// The iteration of thesis §3.4.3: fit T to the current boundary and its image, then the cheapest
// closed path around the feature for that T, until the boundary repeats, the energy settles or
// the iteration cap is reached.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "optimal_boundary_detail.h"
#include "uv_locator.h"

namespace lapis::mesh_merge {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Eq. 3.1's cost of edge a-b under the linear part M.
double edge_cost(const Vertices& X, const Vertices& P, const Eigen::Matrix3d& M, int a, int b) {
  const Eigen::Vector3d e = X.row(b) - X.row(a), image = P.row(b) - P.row(a);
  const double c = (M * e - image).norm() * e.norm();
  return std::isnan(c) ? kInf : c;
}

// §3.4.3 step 2: "the rigid transformation between the point sets ∂Ω and ∂Ω*" (Kabsch), and "the
// ratio of average edge lengths of ∂Ω* and ∂Ω" as the scale.
geometry::Similarity3 fit_boundary_similarity(const Vertices& X, const Vertices& P, const std::vector<int>& loop) {
  const Eigen::Index n = static_cast<Eigen::Index>(loop.size());
  Eigen::MatrixX3d from(n, 3), to(n, 3);
  double length = 0, image_length = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    from.row(i) = X.row(loop[i]), to.row(i) = P.row(loop[i]);
    const int j = loop[(i + 1) % n];
    length += (X.row(j) - X.row(loop[i])).norm(), image_length += (P.row(j) - P.row(loop[i])).norm();
  }
  geometry::Similarity3 T = geometry::fit_similarity(from, to, false);
  T.s = image_length / length;
  T.t = to.colwise().mean().transpose() - T.s * (T.R * from.colwise().mean().transpose());
  return T;
}

// A cut-open path from a cut vertex to its twin as a simple loop of source vertices: where it
// passes both copies of another cut vertex it touches itself there, and the part between the two
// copies is the sub-loop that winds around Ωf (the rest crosses the cut twice).
std::vector<int> simple_loop(const std::vector<int>& path, const std::vector<int>& origin) {
  std::vector<int> loop;
  for (size_t i = 0; i + 1 < path.size(); ++i) loop.push_back(origin[path[i]]);
  for (bool repeated = true; repeated;) {
    repeated = false;
    std::vector<int> seen_at(origin.size(), -1);
    for (size_t i = 0; i < loop.size() && !repeated; ++i) {
      int& first = seen_at[loop[i]];
      if (first >= 0) {
        loop = std::vector<int>(loop.begin() + first, loop.begin() + static_cast<std::ptrdiff_t>(i));
        repeated = true;
      } else {
        first = static_cast<int>(i);
      }
    }
  }
  return loop;
}

}  // namespace

double boundary_energy(const Vertices& source, const Vertices& image, const std::vector<int>& loop,
                       const geometry::Similarity3& T) {
  const Eigen::Matrix3d M = T.linear();
  double E = 0;
  for (size_t i = 0; i < loop.size(); ++i) E += edge_cost(source, image, M, loop[i], loop[(i + 1) % loop.size()]);
  return E;
}

std::vector<int> BoundaryOptimizer::cheapest_loop(const Vertices& image, const geometry::Similarity3& T,
                                                  double* cost) const {
  const geometry::Connectivity& conn = *cut_conn_;
  const Eigen::Matrix3d M = T.linear();
  std::vector<double> edge(static_cast<size_t>(conn.num_edges()));
  for (int e = 0; e < conn.num_edges(); ++e) {
    const int a = origin_[conn.edges()[e][0]], b = origin_[conn.edges()[e][1]];
    edge[e] = too_near_[a] || too_near_[b] ? kInf : edge_cost(source_.V, image, M, a, b);
  }
  const geometry::EdgeCost by_edge = [&edge](int e, int, int) { return edge[e]; };
  const int nv = source_.num_vertices(), m = static_cast<int>(cut_.size());
  double best = kInf;
  int best_k = -1;
  std::vector<int> best_path;
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < m; ++k) {
    geometry::DijkstraOptions o;
    o.target = nv + k;
#pragma omp critical(lapis_optimal_boundary)
    if (options_.prune) o.max_distance = best;
    const geometry::ShortestPaths paths = geometry::dijkstra(conn, {cut_[k]}, by_edge, o);
    const double d = paths.distance[nv + k];
#pragma omp critical(lapis_optimal_boundary)
    if (d < best || (d == best && std::isfinite(d) && k < best_k)) {
      best = d, best_k = k;
      best_path = geometry::extract_path(paths, nv + k);
    }
  }
  if (best_k < 0) {
    if (cost) *cost = kInf;
    return {};
  }
  std::vector<int> loop = detail::canonical_loop(simple_loop(best_path, origin_), source_uv_);
  if (cost) *cost = boundary_energy(source_.V, image, loop, T);
  return loop;
}

OptimalBoundary BoundaryOptimizer::optimize(const Placement2D& placement, const BoundaryProgress& progress) const {
  OptimalBoundary r;
  r.timings = timings_;
  auto t0 = std::chrono::steady_clock::now();
  r.image = Vertices::Constant(source_.num_vertices(), 3, kNaN);
  r.image_uv = Eigen::MatrixX2d::Constant(source_.num_vertices(), 2, kNaN);
  const detail::UvLocator locator(target_region_uv_, target_region_.F);
  for (int v = 0; v < source_.num_vertices(); ++v) {
    if (std::isnan(source_uv_(v, 0))) continue;
    const Eigen::Vector2d q = placement(source_uv_.row(v).transpose());
    const detail::UvHit hit = locator.locate_in_cell(q);
    if (hit.face < 0 || hit.min_weight < -1e-9) continue;
    const Eigen::Vector3d w = hit.weights.cwiseMax(0.0) / hit.weights.cwiseMax(0.0).sum();
    r.image.row(v).setZero();
    for (int j = 0; j < 3; ++j) r.image.row(v) += w(j) * target_region_.V.row(target_region_.F(hit.face, j));
    r.image_uv.row(v) = q.transpose();
  }
  for (int v : outer_)
    if (std::isnan(r.image(v, 0)))
      detail::fail_optimal("source vertex " + std::to_string(v) +
                           " of ∂Ω0 maps outside the target region Ω1 under the placement; move or shrink the band");
  r.timings.map_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  r.user_loop = outer_;
  std::vector<int> loop = outer_, previous;
  r.energy = kInf;
  for (int k = 0;; ++k) {
    const auto t_step = std::chrono::steady_clock::now();
    BoundaryIteration it;
    it.transform = fit_boundary_similarity(source_.V, r.image, loop);
    it.energy = boundary_energy(source_.V, r.image, loop, it.transform);
    it.step_energy = kNaN;
    it.loop_vertices = static_cast<int>(loop.size());
    for (size_t i = 0; i < loop.size(); ++i)
      it.loop_length += (source_.V.row(loop[(i + 1) % loop.size()]) - source_.V.row(loop[i])).norm();
    if (k == 0) r.user_energy = it.energy;
    if (it.energy < r.energy) r.energy = it.energy, r.loop = loop, r.transform = it.transform, r.best_iteration = k;
    const double change = k > 0 ? std::abs(it.energy - r.history.back().energy) : kInf;
    r.history.push_back(it);
    if (progress) progress(k, it);
    if (k > 0 && loop == previous)
      r.stopped_by = "fixed point";
    else if (change <= options_.relative_tolerance * it.energy)
      r.stopped_by = "energy change";
    else if (k == options_.max_iterations)
      r.stopped_by = "iteration cap";
    if (!r.stopped_by.empty()) {
      r.history.back().ms = ms_since(t_step);
      break;
    }
    std::vector<int> next = cheapest_loop(r.image, it.transform, &r.history.back().step_energy);
    if (next.empty())  // ∂Ω0 itself is a finite loop, so this needs its images undefined
      detail::fail_optimal("every closed path around Ωf crosses the outside of Ω1 under the placement");
    r.history.back().ms = ms_since(t_step);
    previous = std::move(loop);
    loop = std::move(next);
  }
  r.timings.iterate_ms = ms_since(t0);
  return r;
}

Placement2D BoundaryOptimizer::suggested_placement() const {
  // uv -> 3D least-squares linear part (3x2) of each map, over its vertices.
  auto uv_to_space = [](const Vertices& V, const Eigen::MatrixX2d& uv, const std::vector<int>& vertices) {
    Eigen::MatrixX2d A(static_cast<Eigen::Index>(vertices.size()), 2);
    Eigen::MatrixX3d B(A.rows(), 3);
    for (Eigen::Index i = 0; i < A.rows(); ++i) A.row(i) = uv.row(vertices[i]), B.row(i) = V.row(vertices[i]);
    A.rowwise() -= A.colwise().mean();
    B.rowwise() -= B.colwise().mean();
    return Eigen::Matrix<double, 3, 2>((A.transpose() * A).ldlt().solve(A.transpose() * B).transpose());
  };
  std::vector<int> band;
  for (int v = 0; v < source_.num_vertices(); ++v)
    if (!std::isnan(source_uv_(v, 0))) band.push_back(v);
  const Eigen::Matrix<double, 3, 2> Js = uv_to_space(source_.V, source_uv_, band);
  const Eigen::Matrix<double, 3, 2> Jt = uv_to_space(target_.V, target_uv_, target_vertex_);
  Placement2D p;
  // Source uv spans the band's size in units of the pin distance; its 3D scale is |Js|.
  p.scale = std::sqrt(Js.squaredNorm() / 2) / std::sqrt(Jt.squaredNorm() / 2);
  // The rotation Q of uv making Jt Q closest to Js: the polar factor of Jtᵀ Js.
  const Eigen::Matrix2d C = Jt.transpose() * Js;
  p.angle = std::atan2(C(1, 0) - C(0, 1), C(0, 0) + C(1, 1));
  // ∂Ω0's uv centroid goes on Ω1's vertex nearest ∂Ω0's 3D centroid (the user placed the source
  // there), or else on Ω1's vertex farthest from its border in uv; at the 3D scale, or smaller
  // until ∂Ω0 maps inside Ω1 with a margin of 15% and the faces under it keep off Ω1's border.
  Eigen::Vector2d uv_centre = Eigen::Vector2d::Zero();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int v : outer_) uv_centre += source_uv_.row(v).transpose(), centre += source_.V.row(v).transpose();
  uv_centre /= static_cast<double>(outer_.size()), centre /= static_cast<double>(outer_.size());
  int nearest = target_vertex_[0];
  for (int v : target_vertex_)
    if ((target_.V.row(v).transpose() - centre).squaredNorm() <
        (target_.V.row(nearest).transpose() - centre).squaredNorm())
      nearest = v;
  const detail::UvLocator locator(target_region_uv_, target_region_.F);
  auto fits = [&](Placement2D q) {
    q.scale *= 1.15;  // a margin: the merge removes the faces under the boundary's image and one more ring
    q.offset = Eigen::Vector2d::Zero();
    q.offset = p(uv_centre) - q(uv_centre);
    for (int v : outer_) {
      const detail::UvHit hit = locator.locate_in_cell(q(source_uv_.row(v).transpose()));
      if (hit.face < 0 || hit.min_weight < -1e-9) return false;
    }
    // And exactly as the merge will see it: the faces under ∂Ω0's image keep off Ω1's border.
    Eigen::MatrixX2d polygon(static_cast<Eigen::Index>(outer_.size()), 2);
    for (size_t i = 0; i < outer_.size(); ++i)
      polygon.row(static_cast<Eigen::Index>(i)) = p(source_uv_.row(outer_[i]).transpose()).transpose();
    return !hole_reaches_border(faces_under(polygon));
  };
  const double full_scale = p.scale;
  for (const Eigen::Vector2d& at : {Eigen::Vector2d(target_uv_.row(nearest).transpose()), deepest_target_point()})
    for (int shrink = 0; shrink < 40; ++shrink) {
      p.scale = full_scale * std::pow(0.85, shrink);
      p.offset = Eigen::Vector2d::Zero();
      p.offset = at - p(uv_centre);
      if (fits(p)) return p;
    }
  p.scale = full_scale;
  p.offset = Eigen::Vector2d::Zero();
  p.offset = target_uv_.row(nearest).transpose() - p(uv_centre);
  return p;
}

// The uv point of Ω1's vertex farthest (edge paths in uv) from Ω1's border.
Eigen::Vector2d BoundaryOptimizer::deepest_target_point() const {
  const geometry::Connectivity conn(target_region_);
  TriMesh flat{Vertices::Zero(target_region_.num_vertices(), 3), target_region_.F};
  flat.V.leftCols(2) = target_region_uv_;
  const geometry::ShortestPaths d =
      geometry::dijkstra(conn, conn.boundary_loops()[0], geometry::edge_length_cost(flat));
  int deepest = 0;
  for (int v = 0; v < target_region_.num_vertices(); ++v)
    if (d.distance[v] > d.distance[deepest]) deepest = v;
  return target_region_uv_.row(deepest).transpose();
}

OptimalBoundary optimal_boundary(const TriMesh& source, const TriMesh& target, const BoundaryRegions& regions,
                                 const Placement2D& placement, const OptimalBoundaryOptions& options) {
  return BoundaryOptimizer(source, target, regions, options).optimize(placement);
}

}  // namespace lapis::mesh_merge
