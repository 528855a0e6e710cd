// BoundaryOptimizer's set-up: the regions and their checks, the fill of ∂Ωf, both conformal
// maps, and the band cut open along the shortest path across it (thesis §3.4.2–3.4.3).
#include "lapis/mesh_merge/optimal_boundary.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>
#include <string>

#include "cut_open.h"
#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/hole_fill.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/lscm.h"
#include "optimal_boundary_detail.h"

namespace lapis::mesh_merge {
namespace {

using geometry::Connectivity;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// Sorted, without duplicates; every face when empty and empty_is_all.
std::vector<int> checked_faces(std::vector<int> faces, int num_faces, const char* region, bool empty_is_all) {
  if (faces.empty() && empty_is_all) {
    faces.resize(static_cast<size_t>(num_faces));
    std::iota(faces.begin(), faces.end(), 0);
  }
  for (int f : faces)
    if (f < 0 || f >= num_faces)
      detail::fail_optimal(std::string(region) + " face " + std::to_string(f) + " is out of range [0, " +
                           std::to_string(num_faces) + ")");
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

// `mesh` restricted to its used vertices: the compact mesh and each compact vertex's index.
TriMesh compacted(TriMesh mesh, std::vector<int>& original) {
  const std::vector<int> map = geometry::remove_unreferenced_vertices(mesh);
  original.assign(static_cast<size_t>(mesh.num_vertices()), -1);
  for (size_t v = 0; v < map.size(); ++v)
    if (map[v] >= 0) original[map[v]] = static_cast<int>(v);
  return mesh;
}

std::string topology_of(const Connectivity& conn) {
  return std::to_string(geometry::connected_components(conn).count) + " part(s), " +
         std::to_string(conn.boundary_loops().size()) + " boundary loop(s), Euler characteristic " +
         std::to_string(geometry::euler_characteristic(conn));
}

// Rotated to start at its lowest vertex index, so equal cycles compare equal.
std::vector<int> starting_at_lowest(std::vector<int> loop) {
  std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
  return loop;
}

}  // namespace

namespace detail {

[[noreturn]] void fail_optimal(const std::string& what) {
  throw InvalidArgument("mesh_merge::optimal_boundary(): " + what);
}

std::vector<int> canonical_loop(std::vector<int> loop, const Eigen::MatrixX2d& uv) {
  double area = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Eigen::Vector2d a = uv.row(loop[i]), b = uv.row(loop[(i + 1) % loop.size()]);
    area += a.x() * b.y() - a.y() * b.x();
  }
  if (area < 0) std::reverse(loop.begin(), loop.end());
  return starting_at_lowest(std::move(loop));
}

}  // namespace detail

Eigen::Vector2d Placement2D::operator()(const Eigen::Vector2d& uv) const {
  const double c = std::cos(angle), s = std::sin(angle);
  return scale * Eigen::Vector2d(c * uv.x() - s * uv.y(), s * uv.x() + c * uv.y()) + offset;
}

BoundaryOptimizer::BoundaryOptimizer(TriMesh source, TriMesh target, BoundaryRegions regions,
                                     OptimalBoundaryOptions options)
    : source_(std::move(source)), target_(std::move(target)), options_(options) {
  if (options_.max_iterations < 0 || !(options_.relative_tolerance >= 0) || options_.max_exact_fill < 3 ||
      options_.feature_clearance < 0)
    detail::fail_optimal(
        "options out of range (max_iterations >= 0, relative_tolerance >= 0, max_exact_fill >= 3, "
        "feature_clearance >= 0)");
  const std::vector<int> roi = checked_faces(std::move(regions.roi_faces), source_.num_faces(), "Ω0", true);
  feature_faces_ = checked_faces(std::move(regions.feature_faces), source_.num_faces(), "Ωf", false);
  target_faces_ = checked_faces(std::move(regions.target_faces), target_.num_faces(), "Ω1", true);
  if (feature_faces_.empty()) detail::fail_optimal("the feature region Ωf is empty");
  for (int f : feature_faces_)
    if (!std::binary_search(roi.begin(), roi.end(), f))
      detail::fail_optimal("feature face " + std::to_string(f) + " is not in the rough region Ω0");
  std::set_difference(roi.begin(), roi.end(), feature_faces_.begin(), feature_faces_.end(),
                      std::back_inserter(band_faces_));
  find_loops();
  auto t0 = std::chrono::steady_clock::now();
  const TriMesh band = geometry::with_faces(source_, band_faces_);
  parameterize_band(band);
  parameterize_target();
  t0 = std::chrono::steady_clock::now();
  const Connectivity band_conn(band);  // the cut and the clearance walk the same band
  cut_band(band, band_conn);
  keep_clear_of_feature(band_conn);
  timings_.cut_ms = ms_since(t0);
}

void BoundaryOptimizer::find_loops() {
  const Connectivity feature(geometry::with_faces(source_, feature_faces_));
  if (geometry::connected_components(feature).count != 1 || feature.boundary_loops().size() != 1)
    detail::fail_optimal("the feature region Ωf must be connected with one boundary loop; it has " +
                         topology_of(feature));
  const Connectivity rough(geometry::with_faces(source_, [&] {
    std::vector<int> all = band_faces_;
    all.insert(all.end(), feature_faces_.begin(), feature_faces_.end());
    return all;
  }()));
  if (rough.boundary_loops().size() != 1)
    detail::fail_optimal(
        "the band Ω0 \\ Ωf must be an annulus between ∂Ω0 and ∂Ωf, so Ω0 needs one boundary loop; it has " +
        topology_of(rough));
  const std::vector<int>& border = rough.boundary_loops()[0];
  const std::set<int> on_border(border.begin(), border.end());
  for (int v : feature.boundary_loops()[0])
    if (on_border.count(v))
      detail::fail_optimal("the feature region Ωf touches Ω0's border at source vertex " + std::to_string(v) +
                           "; Ω0 must surround it with a band");
  const Connectivity band(geometry::with_faces(source_, band_faces_));
  if (band_faces_.empty() || geometry::connected_components(band).count != 1 || band.boundary_loops().size() != 2 ||
      geometry::euler_characteristic(band) != 0)
    detail::fail_optimal("the band Ω0 \\ Ωf must be an annulus between ∂Ω0 and ∂Ωf; it has " + topology_of(band));
  // The band's loops run with the band on their left: ∂Ω0 then has Ωf on its left too, ∂Ωf on
  // its right, so ∂Ωf is reversed to run the same way round.
  for (const auto& loop : band.boundary_loops()) {
    if (on_border.count(loop[0]))
      outer_ = starting_at_lowest(loop);
    else
      inner_ = starting_at_lowest(std::vector<int>(loop.rbegin(), loop.rend()));
  }
}

void BoundaryOptimizer::parameterize_band(const TriMesh& band) {
  auto t0 = std::chrono::steady_clock::now();
  // The fill runs against the band's own loop (the reverse of inner_).
  const geometry::HoleFill fill =
      geometry::minimal_area_fill(source_.V, std::vector<int>(inner_.rbegin(), inner_.rend()), options_.max_exact_fill);
  fill_is_fan_ = fill.fan;
  TriMesh filled;
  filled.V.resize(source_.num_vertices() + fill.added.rows(), 3);
  filled.V << source_.V, fill.added;
  filled.F.resize(band.num_faces() + fill.faces.rows(), 3);
  filled.F << band.F, fill.faces;
  timings_.fill_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  std::vector<int> original;
  const TriMesh disk = compacted(filled, original);
  std::vector<int> local(static_cast<size_t>(filled.num_vertices()), -1);
  for (size_t i = 0; i < original.size(); ++i) local[original[i]] = static_cast<int>(i);
  std::vector<int> outer_local;
  for (int v : outer_) outer_local.push_back(local[v]);
  const Eigen::MatrixX2d uv = lscm_pinned_on_loop(disk, outer_local, false);
  source_uv_ = Eigen::MatrixX2d::Constant(source_.num_vertices(), 2, kNaN);
  for (size_t i = 0; i < original.size(); ++i)
    if (original[i] < source_.num_vertices()) source_uv_.row(original[i]) = uv.row(static_cast<Eigen::Index>(i));
  timings_.lscm_ms = ms_since(t0);
}

void BoundaryOptimizer::parameterize_target() {
  const auto t0 = std::chrono::steady_clock::now();
  const Connectivity region(geometry::with_faces(target_, target_faces_));
  if (geometry::connected_components(region).count != 1 || region.boundary_loops().size() != 1 ||
      geometry::euler_characteristic(region) != 1)
    detail::fail_optimal("the target region Ω1 must be a disk; it has " + topology_of(region));
  target_region_ = compacted(geometry::with_faces(target_, target_faces_), target_vertex_);
  std::vector<int> local(static_cast<size_t>(target_.num_vertices()), -1);
  for (size_t i = 0; i < target_vertex_.size(); ++i) local[target_vertex_[i]] = static_cast<int>(i);
  std::vector<int> loop;
  for (int v : region.boundary_loops()[0]) loop.push_back(local[v]);
  target_region_uv_ = lscm_pinned_on_loop(target_region_, loop, true);
  target_uv_ = Eigen::MatrixX2d::Constant(target_.num_vertices(), 2, kNaN);
  for (size_t i = 0; i < target_vertex_.size(); ++i)
    target_uv_.row(target_vertex_[i]) = target_region_uv_.row(static_cast<Eigen::Index>(i));
  timings_.lscm_ms += ms_since(t0);
}

// §3.4.3: "the shortest path from a vertex on ∂Ω0 to a vertex on ∂Ωfeature", as straight and
// short as possible: Dijkstra by edge length from all of ∂Ω0 at once, never along either border,
// to the nearest vertex of ∂Ωf. Then every cut vertex gets a twin on the path's other side.
void BoundaryOptimizer::cut_band(const TriMesh& band, const Connectivity& conn) {
  const auto length = geometry::edge_length_cost(band);
  const geometry::ShortestPaths paths = geometry::dijkstra(
      conn, outer_, [&](int e, int a, int b) { return conn.is_boundary_edge(e) ? kInf : length(e, a, b); });
  int sink = -1;
  for (int v : inner_)
    if (std::isfinite(paths.distance[v]) && (sink < 0 || paths.distance[v] < paths.distance[sink])) sink = v;
  if (sink < 0) detail::fail_optimal("no path crosses the band from ∂Ω0 to ∂Ωf");
  cut_ = geometry::extract_path(paths, sink);
  const detail::CutOpen open = detail::cut_open(conn, band.F, cut_, false);
  if (open.failed_at >= 0)
    detail::fail_optimal("the band cannot be cut open at source vertex " + std::to_string(open.failed_at) +
                         " (its faces there do not form one fan)");
  const int nv = source_.num_vertices();
  cut_band_.V.resize(nv + static_cast<Eigen::Index>(cut_.size()), 3);
  cut_band_.V.topRows(nv) = source_.V;
  origin_.resize(static_cast<size_t>(nv));
  std::iota(origin_.begin(), origin_.end(), 0);
  for (size_t k = 0; k < cut_.size(); ++k) {
    cut_band_.V.row(nv + static_cast<Eigen::Index>(k)) = source_.V.row(cut_[k]);
    origin_.push_back(cut_[k]);
  }
  cut_band_.F = open.faces;
  cut_conn_ = std::make_shared<const Connectivity>(cut_band_);
}

// The band vertices fewer than feature_clearance edges from ∂Ωf, which the boundary step may
// not use, and a check that a closed path around Ωf remains: some cut vertex still reaches its
// twin through the cut-open band's other vertices.
void BoundaryOptimizer::keep_clear_of_feature(const Connectivity& band) {
  const int nv = source_.num_vertices(), clearance = options_.feature_clearance;
  too_near_.assign(static_cast<size_t>(nv), 0);
  if (clearance == 0) return;
  const geometry::ShortestPaths steps = geometry::dijkstra(band, inner_, [](int, int, int) { return 1.0; });
  for (int v = 0; v < nv; ++v) too_near_[v] = steps.distance[v] < clearance;
  const Connectivity& conn = *cut_conn_;
  std::vector<int> component(static_cast<size_t>(cut_band_.num_vertices()));
  std::iota(component.begin(), component.end(), 0);
  auto root = [&](int v) {
    while (component[v] != v) v = component[v] = component[component[v]];
    return v;
  };
  for (const auto& e : conn.edges())
    if (!too_near_[origin_[e[0]]] && !too_near_[origin_[e[1]]]) component[root(e[0])] = root(e[1]);
  for (size_t k = 0; k < cut_.size(); ++k)
    if (!too_near_[cut_[k]] && root(cut_[k]) == root(nv + static_cast<int>(k))) return;
  detail::fail_optimal("Ω0 leaves no closed path around Ωf at least " + std::to_string(clearance) +
                       " edge(s) from it (feature_clearance); paint a wider rough region or lower the clearance");
}

}  // namespace lapis::mesh_merge
