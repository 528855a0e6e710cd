// lapis.mesh_merge in Python: Poisson merging of a source part onto a target along paired
// boundary loops (independent, dependent and transition modes), and along the optimal boundary
// of a band around a feature. Each returns (V, F, report) with the report as a dict.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>

#include "arrays.h"
#include "bindings.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/merge.h"
#include "lapis/mesh_merge/metrics.h"
#include "lapis/mesh_merge/optimal_boundary.h"
#include "lapis/mesh_merge/pairs_file.h"
#include "lapis/mesh_merge/regions_file.h"

namespace lapis::python {
namespace {

using namespace lapis::mesh_merge;
using namespace pybind11::literals;

// Each pair: a (k, 2) array or a sequence of (source vertex, target vertex) keys.
std::vector<LoopPair> to_pairs(const py::handle& pairs) {
  std::vector<LoopPair> out;
  for (const py::handle& p : pairs) {
    const auto keys = to_dense(py::array_t<double>::ensure(p), "pairs[i]", 2);
    LoopPair pair;
    for (Eigen::Index k = 0; k < keys.rows(); ++k)
      pair.keys.push_back({static_cast<int>(keys(k, 0)), static_cast<int>(keys(k, 1))});
    out.push_back(std::move(pair));
  }
  return out;
}

py::list pairs_list(const std::vector<LoopPair>& pairs) {
  py::list out;
  for (const LoopPair& p : pairs) {
    Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor> keys(static_cast<Eigen::Index>(p.keys.size()), 2);
    for (size_t k = 0; k < p.keys.size(); ++k)
      keys.row(static_cast<Eigen::Index>(k)) << p.keys[k].source, p.keys[k].target;
    out.append(to_numpy(std::move(keys)));
  }
  return out;
}

py::dict report(const TriMesh& source, const TriMesh& target, MergeResult& r) {
  const SeamQuality q = seam_quality(target, r);
  const DetailPreservation d = detail_preservation(source, r);
  return py::dict(
      "target_map"_a = to_numpy(std::move(r.target_map)), "source_map"_a = to_numpy(std::move(r.source_map)),
      "seam_vertices"_a = to_numpy(std::move(r.seam_vertices)), "strip_faces"_a = to_numpy(std::move(r.strip_faces)),
      "smoothed"_a = to_numpy(std::move(r.smoothed)),
      "transition_vertices"_a = to_numpy(std::move(r.transition_vertices)),
      "transition_share"_a = to_numpy(std::move(r.transition_share)), "refine_levels"_a = r.refine_levels,
      "roi_vertices"_a = r.roi_vertices,
      "timings_ms"_a =
          py::dict("setup"_a = r.timings.setup_ms, "solve"_a = r.timings.solve_ms, "zip"_a = r.timings.zip_ms,
                   "smooth"_a = r.timings.smooth_ms, "total"_a = r.timings.total_ms),
      "seam"_a =
          py::dict("valid"_a = q.valid(), "boundary_edges"_a = q.seam_boundary_edges,
                   "non_manifold_edges"_a = q.non_manifold_edges, "non_manifold_vertices"_a = q.non_manifold_vertices,
                   "degenerate_faces"_a = q.degenerate_faces, "min_strip_angle_deg"_a = q.min_strip_angle_deg,
                   "max_target_displacement"_a = q.max_target_displacement,
                   "dihedral_mean_deg"_a = q.seam_dihedral_mean_deg, "dihedral_max_deg"_a = q.seam_dihedral_max_deg),
      "detail"_a = py::dict("laplacian_residual"_a = d.laplacian_residual, "max_distance"_a = d.max_distance,
                            "mean_distance"_a = d.mean_distance, "turn_deg"_a = d.turn_deg));
}

py::tuple result(const TriMesh& source, const TriMesh& target, MergeResult&& r) {
  py::dict rep = report(source, target, r);
  return py::make_tuple(to_numpy(std::move(r.mesh.V)), to_numpy(std::move(r.mesh.F)), rep);
}

MergeMode mode_from_name(const std::string& mode) {
  if (mode == "independent") return MergeMode::Independent;
  if (mode == "dependent") return MergeMode::Dependent;
  if (mode == "transition") return MergeMode::Transition;
  throw InvalidArgument("mode must be independent, dependent or transition (merge_optimal: optimal), not '" + mode +
                        "'");
}

py::tuple merge_loops(const py::handle& sV, const py::handle& sF, const py::handle& tV, const py::handle& tF,
                      const py::handle& pairs, const std::string& mode, const py::handle& handles,
                      const py::handle& features, int smooth_iterations, int smooth_rings, double smooth_lambda,
                      double refine_ratio, int refine_levels, double roi_width, const py::object& source_width,
                      const py::object& target_width, double transition_weight, const std::string& keep,
                      bool configuration_dependent) {
  const TriMesh source{to_vertices(sV, "source_V"), to_faces(sF, "source_F")};
  const TriMesh target{to_vertices(tV, "target_V"), to_faces(tF, "target_F")};
  const std::vector<LoopPair> p = to_pairs(pairs);
  MergeOptions o;
  o.mode = mode_from_name(mode);
  o.handles = to_indices(handles, "handles");
  for (const py::handle& f : features) o.features.push_back(to_indices(f, "features[i]"));
  o.smooth_iterations = smooth_iterations, o.smooth_rings = smooth_rings, o.smooth_lambda = smooth_lambda;
  o.refine_ratio = refine_ratio, o.refine_levels = refine_levels, o.roi_width = roi_width;
  o.transition.weight = transition_weight;
  if (keep != "source" && keep != "target") throw InvalidArgument("keep must be source or target, not '" + keep + "'");
  o.transition.keep = keep == "source" ? TransitionKeep::Source : TransitionKeep::Target;
  o.transition.configuration_dependent = configuration_dependent;
  MergeResult r;
  {
    py::gil_scoped_release release;
    if (o.mode == MergeMode::Transition && (source_width.is_none() || target_width.is_none())) {
      // As `lapis merge`: a width not given is the suggested one.
      const double suggested = suggested_transition_width(source, target, p);
      py::gil_scoped_acquire acquire;
      o.transition.source_width = source_width.is_none() ? suggested : source_width.cast<double>();
      o.transition.target_width = target_width.is_none() ? suggested : target_width.cast<double>();
    } else if (o.mode == MergeMode::Transition) {
      py::gil_scoped_acquire acquire;
      o.transition.source_width = source_width.cast<double>();
      o.transition.target_width = target_width.cast<double>();
    }
    r = merge(source, target, p, o);
  }
  return result(source, target, std::move(r));
}

py::tuple merge_optimal(const py::handle& sV, const py::handle& sF, const py::handle& tV, const py::handle& tF,
                        const py::dict& regions, int max_iterations, int smooth_iterations, bool hold_feature) {
  const TriMesh source{to_vertices(sV, "source_V"), to_faces(sF, "source_F")};
  const TriMesh target{to_vertices(tV, "target_V"), to_faces(tF, "target_F")};
  BoundaryRegions b;
  auto faces = [&](const char* key, std::vector<int>& out) {
    if (regions.contains(key)) out = to_indices(regions[key], key);
  };
  faces("roi_faces", b.roi_faces);
  faces("feature_faces", b.feature_faces);
  faces("target_faces", b.target_faces);
  OptimalBoundaryOptions options;
  options.max_iterations = max_iterations;
  MergeOptions merge_options;
  merge_options.mode = MergeMode::OptimalBoundary;
  merge_options.smooth_iterations = smooth_iterations;
  merge_options.hold_feature = hold_feature;
  MergeResult r;
  OptimalBoundary boundary;
  {
    py::gil_scoped_release release;
    const BoundaryOptimizer optimizer(source, target, b, options);
    boundary = optimizer.optimize(optimizer.suggested_placement());
    r = optimizer.merge(boundary, merge_options);
  }
  const double feature = feature_distortion(source, r, geometry::vertices_of_faces(source, b.feature_faces));
  py::tuple out = result(source, target, std::move(r));
  py::dict rep = out[2];
  rep["feature_distortion"] = feature;
  rep["boundary"] = to_numpy(std::move(boundary.loop));
  rep["energy"] = boundary.energy, rep["user_energy"] = boundary.user_energy;
  rep["iterations"] = boundary.history.size(), rep["stopped_by"] = boundary.stopped_by;
  return out;
}

}  // namespace

void bind_merge(py::module_& m) {
  m.def("merge", &merge_loops, "source_V"_a, "source_F"_a, "target_V"_a, "target_F"_a, "pairs"_a,
        "mode"_a = "independent", "handles"_a = py::list(), "features"_a = py::list(),
        "smooth_iterations"_a = MergeOptions{}.smooth_iterations, "smooth_rings"_a = MergeOptions{}.smooth_rings,
        "smooth_lambda"_a = MergeOptions{}.smooth_lambda, "refine_ratio"_a = MergeOptions{}.refine_ratio,
        "refine_levels"_a = MergeOptions{}.refine_levels, "roi_width"_a = 0.0, "source_width"_a = py::none(),
        "target_width"_a = py::none(), "transition_weight"_a = TransitionOptions{}.weight, "keep"_a = "source",
        "configuration_dependent"_a = false,
        R"(Poisson mesh merging (thesis §3.3): the source part deformed onto the target's boundary loops,
zipped and smoothed. Returns (V, F, report): the merged mesh (target part first) and a dict with
target_map / source_map (merged index per input vertex, -1 if removed), the seam vertices and
strip faces, timings_ms, and the seam and detail metrics of `lapis merge`.

pairs: one entry per merging loop pair, a (k, 2) array of key (source vertex, target vertex)
correspondences on the two loops. mode: 'independent' (§3.3.1), 'dependent' (§3.3.2: the
source stays where placed, handles fixed, roi_width band) or 'transition' (§3.3.3: overlapped
bands of source_width / target_width, the suggested width when not given; keep: whose band
stays; configuration_dependent: §3.3.2's boundary conditions). features (independent mode,
§3.5): source vertex lists that keep their shape. Raises InvalidArgument with the C++ message
for a bad pair, mode or option.)");
  m.def("merge_optimal", &merge_optimal, "source_V"_a, "source_F"_a, "target_V"_a, "target_F"_a, "regions"_a,
        "max_iterations"_a = OptimalBoundaryOptions{}.max_iterations,
        "smooth_iterations"_a = MergeOptions{}.smooth_iterations, "hold_feature"_a = MergeOptions{}.hold_feature,
        R"(Merging along the optimal boundary (thesis §3.4) of a band around a feature, from the suggested
placement. regions: a dict of face index arrays 'roi_faces' (Ω0, absent: every source face),
'feature_faces' (Ωf) and 'target_faces' (Ω1, absent: every target face), as read_regions()
gives. hold_feature: Ωf moves by one similarity (§3.5's shared gradient); False: it bends with
the rest, as §3.4.1 merges. Returns (V, F, report) as merge() does, the report with the boundary
loop, its energy, the user boundary's energy, how the iteration stopped and feature_distortion
(Ωf's largest distance from a similar copy of itself, over its size).)");
  m.def(
      "read_pairs", [](const std::filesystem::path& path) { return pairs_list(read_pairs_file(path)); }, "path"_a,
      "A pairs file of `lapis merge` as merge()'s pairs: a list of (k, 2) int32 key arrays.");
  m.def(
      "read_regions",
      [](const std::filesystem::path& path, const py::handle& sV, const py::handle& sF, const py::handle& tV,
         const py::handle& tF) {
        const TriMesh source{to_vertices(sV, "source_V"), to_faces(sF, "source_F")};
        const TriMesh target{to_vertices(tV, "target_V"), to_faces(tF, "target_F")};
        BoundaryRegions b = read_regions_file(path, source, target);
        return py::dict("roi_faces"_a = to_numpy(std::move(b.roi_faces)),
                        "feature_faces"_a = to_numpy(std::move(b.feature_faces)),
                        "target_faces"_a = to_numpy(std::move(b.target_faces)));
      },
      "path"_a, "source_V"_a, "source_F"_a, "target_V"_a, "target_F"_a,
      "A regions file of `lapis merge --mode optimal` (vertex regions resolved on the meshes) as face arrays.");
}

}  // namespace lapis::python
