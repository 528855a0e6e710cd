#include "lapis/mesh_merge/merge.h"

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "lapis/geometry/dijkstra.h"
#include "lapis/mesh_merge/constraints.h"
#include "lapis/mesh_merge/refine.h"
#include "lapis/mesh_merge/zip.h"

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
}

// §3.3.2: the vertices near the boundary deform, the rest of the source and the handles stay.
std::vector<int> dependent_roi(const TriMesh& source, const Connectivity& conn,
                               const std::vector<BoundaryCorrespondence>& pairs, const MergeOptions& o) {
  std::vector<int> boundary;
  double perimeter = 0;
  for (const auto& c : pairs) {
    const size_t n = c.source_loop.size();
    for (size_t i = 0; i < n; ++i) {
      boundary.push_back(c.source_loop[i]);
      perimeter += (source.V.row(c.source_loop[(i + 1) % n]) - source.V.row(c.source_loop[i])).norm();
    }
  }
  const double width = o.roi_width > 0 ? o.roi_width : perimeter / (std::numbers::pi * double(pairs.size()));
  geometry::DijkstraOptions d;
  d.max_distance = width;
  const geometry::ShortestPaths sp = geometry::dijkstra(conn, boundary, geometry::edge_length_cost(source), d);
  std::vector<char> keep(static_cast<size_t>(source.num_vertices()), 0);
  for (int h : o.handles) keep[h] = 1;
  std::vector<int> roi;
  for (int v = 0; v < source.num_vertices(); ++v)
    if (sp.distance[v] <= width && !keep[v]) roi.push_back(v);
  for (int v : boundary)
    if (keep[v]) throw InvalidArgument(std::string(kFn) + ": handle vertex " + std::to_string(v) + " lies on the merging boundary");
  return roi;
}

}  // namespace

MergeResult merge(const TriMesh& source_in, const TriMesh& target, const std::vector<LoopPair>& pairs,
                  const MergeOptions& options) {
  const auto t_total = std::chrono::steady_clock::now();
  auto t0 = t_total;
  check_options(source_in, options);
  MergeResult r;
  const Connectivity tconn(target);
  // Validate on the input as given, so errors name the user's indices; then refine.
  check_merge_input(source_in, Connectivity(source_in), target, tconn, pairs);
  r.source_rest = source_in;
  if (options.mode == MergeMode::Independent)
    r.refine_levels = refine_short_boundary(r.source_rest, options.refine_ratio, options.refine_levels);
  const TriMesh& source = r.source_rest;
  const Connectivity sconn(source);
  const std::vector<BoundaryCorrespondence> corr = correspond_boundaries(source, sconn, target, tconn, pairs);
  const bool dependent = options.mode == MergeMode::Dependent;
  const std::vector<BoundaryConstraint> cons = boundary_constraints(source, target, corr, dependent);

  mesh_deform::Selection sel;
  mesh_deform::HandleTransforms tf;
  if (dependent) {
    sel.roi = dependent_roi(source, sconn, corr, options);
  } else {
    sel.roi.resize(static_cast<size_t>(source.num_vertices()));
    for (int v = 0; v < source.num_vertices(); ++v) sel.roi[v] = v;
  }
  add_region_handles(source, cons, sel, tf);
  for (const auto& k : cons) r.source_boundary.push_back(k.vertex);
  r.roi_vertices = static_cast<int>(sel.roi.size());
  mesh_deform::ImplicitLaplacianDeformer deformer(source, options.implicit);
  deformer.set_selection(std::move(sel));
  deformer.precompute();
  r.timings.setup_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  r.source_deformed = deformer.deform(tf);
  r.solver = deformer.stats();
  r.timings.solve_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  TriMesh deformed{r.source_deformed, source.F};
  ZipResult z = zip_seams(target, deformed, corr);
  r.mesh = std::move(z.mesh);
  r.target_map = std::move(z.target_map);
  r.source_map.assign(z.source_map.begin(), z.source_map.begin() + source_in.num_vertices());
  r.strip_faces = std::move(z.strip_faces);
  r.seam_vertices = std::move(z.seam_vertices);
  r.timings.zip_ms = ms_since(t0);

  t0 = std::chrono::steady_clock::now();
  if (options.smooth_iterations > 0) {
    r.smoothed = seam_band(r.mesh, r.seam_vertices, options.smooth_rings);
    umbrella_smooth(r.mesh, r.smoothed, options.smooth_iterations, options.smooth_lambda);
  }
  r.timings.smooth_ms = ms_since(t0);
  r.timings.total_ms = ms_since(t_total);
  return r;
}

}  // namespace lapis::mesh_merge
