#include "lapis/mesh_merge/merge.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "boundary_checked.h"
#include "lapis/core/format.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/mesh_merge/constraints.h"
#include "lapis/mesh_merge/refine.h"
#include "lapis/mesh_merge/transition.h"
#include "lapis/mesh_merge/zip.h"
#include "transition_merge.h"

namespace lapis::mesh_merge {

namespace {

constexpr const char* kFn = "mesh_merge::merge()";

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void check_options(const TriMesh& source, const MergeOptions& o) {
  auto fail = [](const std::string& what) { throw InvalidArgument(std::string(kFn) + ": " + what); };
  if (o.smooth_iterations < 0 || o.smooth_rings < 0) fail("smooth_iterations and smooth_rings must be >= 0");
  if (!(o.smooth_lambda > 0 && o.smooth_lambda <= 1)) fail("smooth_lambda must be in (0, 1]");
  if (!(o.refine_ratio >= 0) || o.refine_levels < 0) fail("refine_ratio and refine_levels must be >= 0");
  if (!(o.roi_width >= 0) || !std::isfinite(o.roi_width)) fail("roi_width must be finite and >= 0");
  for (int h : o.handles)
    if (h < 0 || h >= source.num_vertices()) fail("handle vertex " + std::to_string(h) + " out of range");
  if (!o.features.empty() && o.mode != MergeMode::Independent)
    fail("features (§3.5) need Independent mode; Dependent mode keeps parts fixed through handles");
  for (size_t f = 0; f < o.features.size(); ++f)
    for (int v : o.features[f])
      if (v < 0 || v >= source.num_vertices())
        fail("feature " + std::to_string(f) + ": vertex " + std::to_string(v) + " out of range");
  if (o.mode == MergeMode::OptimalBoundary)
    fail("OptimalBoundary mode merges along a boundary it finds, not given loops: use BoundaryOptimizer::merge()");
  if (o.mode == MergeMode::Transition) {
    const TransitionOptions& t = o.transition;
    // §3.3.3: the user specifies the widths; there is no width that suits every mesh.
    if (!(t.source_width > 0) || !(t.target_width > 0) || !std::isfinite(t.source_width) ||
        !std::isfinite(t.target_width))
      fail("transition source_width and target_width must be finite and > 0 (thesis §3.3.3: one width per mesh), got " +
           format_number(t.source_width) + " and " + format_number(t.target_width));
    if (!(t.weight > 0) || !std::isfinite(t.weight)) fail("transition weight w_T must be finite and > 0");
  }
}

}  // namespace

namespace detail {

// §3.3.2: the vertices near the boundary deform, the rest of the source and the handles stay.
std::vector<int> dependent_roi(const TriMesh& source, const Connectivity& conn, const MergeOptions& o) {
  std::vector<int> boundary;
  double perimeter = 0;
  const auto& loops = conn.boundary_loops();
  for (const auto& loop : loops) {
    const size_t n = loop.size();
    for (size_t i = 0; i < n; ++i) {
      boundary.push_back(loop[i]);
      perimeter += (source.V.row(loop[(i + 1) % n]) - source.V.row(loop[i])).norm();
    }
  }
  const double width = o.roi_width > 0 ? o.roi_width : perimeter / (std::numbers::pi * double(loops.size()));
  geometry::DijkstraOptions d;
  d.max_distance = width;
  const geometry::ShortestPaths sp = geometry::dijkstra(conn, boundary, geometry::edge_length_cost(source), d);
  std::vector<char> keep(static_cast<size_t>(source.num_vertices()), 0);
  for (int h : o.handles) keep[h] = 1;
  for (int v : boundary)
    if (keep[v])
      throw InvalidArgument(std::string(kFn) + ": handle vertex " + std::to_string(v) +
                            " lies on the merging boundary");
  std::vector<int> roi;
  for (int v = 0; v < source.num_vertices(); ++v)
    if (sp.distance[v] <= width && !keep[v]) roi.push_back(v);
  return roi;
}

}  // namespace detail

struct Merger::Impl {
  Connectivity conn_in;  // of the source as given: pairs are checked against it
  TriMesh rest;          // the refined source the deformer works on
  Connectivity conn;
  int refine_levels = 0;
  int roi_vertices = 0;
  std::vector<int> handle_of;  // rest vertex -> region handle index, -1 for non-boundary vertices
  std::unique_ptr<mesh_deform::ImplicitLaplacianDeformer> deformer;
  // Refinement (levels > 0) changes the connectivity; otherwise the source's is the rest's.
  Impl(Connectivity source_conn, TriMesh refined, int levels)
      : conn_in(std::move(source_conn)),
        rest(std::move(refined)),
        conn(levels > 0 ? Connectivity(rest) : conn_in),
        refine_levels(levels) {}
};

Merger::Merger(TriMesh source, MergeOptions options) : source_(std::move(source)), options_(std::move(options)) {
  const auto t0 = std::chrono::steady_clock::now();
  check_options(source_, options_);
  Connectivity source_conn(source_);
  check_merge_source(source_, source_conn);
  if (options_.mode == MergeMode::Transition) {
    // Nothing to prefactorize: the system couples the source with the target's band.
    impl_ = std::make_unique<Impl>(std::move(source_conn), source_, 0);
    precompute_ms_ = ms_since(t0);
    return;
  }
  TriMesh refined = source_;
  int levels = 0;
  if (options_.mode == MergeMode::Independent)
    levels = refine_short_boundary(refined, options_.refine_ratio, options_.refine_levels);
  impl_ = std::make_unique<Impl>(std::move(source_conn), std::move(refined), levels);
  Impl& m = *impl_;
  mesh_deform::Selection sel;
  if (options_.mode == MergeMode::Dependent) {
    sel.roi = detail::dependent_roi(m.rest, m.conn, options_);
  } else {
    sel.roi.resize(static_cast<size_t>(m.rest.num_vertices()));
    for (int v = 0; v < m.rest.num_vertices(); ++v) sel.roi[v] = v;
  }
  m.roi_vertices = static_cast<int>(sel.roi.size());
  m.handle_of.assign(static_cast<size_t>(m.rest.num_vertices()), -1);
  for (const auto& loop : m.conn.boundary_loops())
    for (int v : loop) {
      m.handle_of[v] = static_cast<int>(sel.region_handles.size());
      sel.region_handles.push_back({v});
    }
  m.deformer = std::make_unique<mesh_deform::ImplicitLaplacianDeformer>(m.rest, options_.implicit);
  for (size_t f = 0; f < options_.features.size(); ++f)
    for (int v : options_.features[f])
      if (m.handle_of[v] >= 0)
        throw InvalidArgument(std::string(kFn) + ": feature " + std::to_string(f) + ": vertex " + std::to_string(v) +
                              " lies on the merging boundary");
  m.deformer->set_shared_gradients(options_.features);  // refinement only appended vertices
  m.deformer->set_selection(std::move(sel));
  m.deformer->precompute();
  precompute_ms_ = ms_since(t0);
}

Merger::~Merger() = default;

void Merger::set_smoothing(int iterations, int rings, double lambda) {
  MergeOptions o = options_;
  o.smooth_iterations = iterations, o.smooth_rings = rings, o.smooth_lambda = lambda;
  check_options(source_, o);
  options_ = std::move(o);
}

MergeResult Merger::merge(const TriMesh& target, const std::vector<LoopPair>& pairs) {
  const auto t_total = std::chrono::steady_clock::now();
  if (options_.mode == MergeMode::Transition) {
    MergeResult r = detail::merge_with_transition(source_, target, pairs, options_);
    r.timings.total_ms = ms_since(t_total);
    return r;
  }
  auto t0 = t_total;
  Impl& m = *impl_;
  MergeResult r;
  const Connectivity tconn(target);
  // Checked on the source as given, so errors name the user's indices; refinement only
  // appended vertices (splitting boundary edges), so the keys mean the same on the refined
  // source and its checks still hold. The source itself was checked by the constructor.
  check_merge_pairs(source_, m.conn_in, target, tconn, pairs);
  const std::vector<BoundaryCorrespondence> corr =
      detail::correspond_checked_boundaries(m.rest, m.conn, target, tconn, pairs);
  const std::vector<BoundaryConstraint> cons =
      boundary_constraints(m.rest, target, corr, options_.mode == MergeMode::Dependent);
  mesh_deform::Selection order;
  mesh_deform::HandleTransforms by_pair, tf;
  add_region_handles(m.rest, cons, order, by_pair);
  tf.regions.resize(by_pair.regions.size());
  for (size_t k = 0; k < cons.size(); ++k) {
    tf.regions[m.handle_of[cons[k].vertex]] = by_pair.regions[k];
    r.source_boundary.push_back(cons[k].vertex);
  }
  r.source_rest = m.rest;
  r.refine_levels = m.refine_levels;
  r.roi_vertices = m.roi_vertices;
  r.timings.setup_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  r.source_deformed = m.deformer->deform(tf);
  r.solver = m.deformer->report();
  r.timings.solve_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  ZipResult z = zip_seams(target, TriMesh{r.source_deformed, m.rest.F}, corr);
  r.mesh = std::move(z.mesh);
  r.target_map = std::move(z.target_map);
  r.source_map.assign(z.source_map.begin(), z.source_map.begin() + source_.num_vertices());
  r.strip_faces = std::move(z.strip_faces);
  r.seam_vertices = std::move(z.seam_vertices);
  r.timings.zip_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  if (options_.smooth_iterations > 0) {
    r.smoothed = seam_band(r.mesh, r.seam_vertices, options_.smooth_rings);
    umbrella_smooth(r.mesh, r.smoothed, options_.smooth_iterations, options_.smooth_lambda);
    unfold_seam(r.mesh, r.strip_faces, r.smoothed);
  }
  flip_thin_diagonals(r.mesh, r.strip_faces);
  r.timings.smooth_ms = ms_since(t0);
  r.timings.total_ms = ms_since(t_total);
  return r;
}

namespace {

constexpr const char* kSuggest = "mesh_merge::suggested_transition_width()";

// The boundary loop of `mesh` through vertex v (a pair's first key), starting at v: the band
// is cut from there.
std::vector<int> loop_through(const Connectivity& conn, int v, int n, const char* side) {
  if (v < 0 || v >= n)
    throw InvalidArgument(std::string(kSuggest) + ": " + side + " key vertex " + std::to_string(v) + " out of range");
  for (std::vector<int> loop : conn.boundary_loops())
    if (const auto at = std::find(loop.begin(), loop.end(), v); at != loop.end()) {
      std::rotate(loop.begin(), at, loop.end());
      return loop;
    }
  throw InvalidArgument(std::string(kSuggest) + ": " + side + " key vertex " + std::to_string(v) +
                        " is not on a boundary loop");
}

}  // namespace

double suggested_transition_width(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs) {
  Connectivity sconn(source), tconn(target);
  std::vector<std::vector<int>> source_loops, target_loops;
  double source_perimeter = 0, target_perimeter = 0;
  for (const LoopPair& p : pairs) {
    if (p.keys.empty()) continue;
    source_loops.push_back(loop_through(sconn, p.keys[0].source, source.num_vertices(), "source"));
    target_loops.push_back(loop_through(tconn, p.keys[0].target, target.num_vertices(), "target"));
    source_perimeter += loop_perimeter(source.V, source_loops.back());
    target_perimeter += loop_perimeter(target.V, target_loops.back());
  }
  if (target_loops.empty() || !(source_perimeter > 0) || !(target_perimeter > 0)) return 0.0;
  // Widths are in target units; the merge scales the source so that its loops' perimeter is
  // the target's (TransitionOptions), and so does the check of its bands here.
  TriMesh scaled = source, refined = target;
  scaled.V *= target_perimeter / source_perimeter;
  // A fifth of the loops' mean diameter (perimeter / π), shrunk until every band is an annulus
  // whose rim lies inside its mesh: the largest band the merge accepts, within 2⁻⁸ of that start.
  constexpr double kShrink = 0.75;
  constexpr int kTries = 20;
  const double start = 0.2 * target_perimeter / std::numbers::pi / static_cast<double>(target_loops.size());
  std::string why;
  double width = start;
  const auto largest = [&] {
    width = start;
    for (int k = 0; k < kTries; ++k, width *= kShrink) {
      bool all = true;
      for (size_t p = 0; p < target_loops.size() && all; ++p)
        all = band_is_annulus(refined, tconn, target_loops[p], width, "target", &why) &&
              band_is_annulus(scaled, sconn, source_loops[p], width, "source", &why);
      if (all) return width;
    }
    return 0.0;
  };
  if (const double w = largest(); w > 0) return w;
  // Where a mesh reaches back to its loop within a triangle, no band is an annulus until the
  // edges there are split, as the merge then splits them (refine.h).
  const int added =
      separate_loop_neighbourhoods(scaled, source_loops) + separate_loop_neighbourhoods(refined, target_loops);
  if (added > 0) {
    sconn = Connectivity(scaled), tconn = Connectivity(refined);
    if (const double w = largest(); w > 0) return w;
  }
  throw InvalidArgument(std::string(kSuggest) + ": no transition width down to " + format_number(width / kShrink) +
                        " gives annular bands next to every merging loop: " + why);
}

MergeResult merge(const TriMesh& source, const TriMesh& target, const std::vector<LoopPair>& pairs,
                  const MergeOptions& options) {
  Merger merger(source, options);
  MergeResult r = merger.merge(target, pairs);
  r.timings.setup_ms += merger.precompute_ms();
  r.timings.total_ms += merger.precompute_ms();
  return r;
}

}  // namespace lapis::mesh_merge
