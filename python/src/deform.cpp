// lapis.mesh_deform in Python: the method registry, the settings structs (attributes named as
// in C++, enums named as on the command line), a Deformer over make_deformer(), distortion
// metrics and the selection files. The package's lapis.Deformer wraps _Deformer with keyword
// options.
#include <pybind11/operators.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <string>

#include "arrays.h"
#include "bindings.h"
#include "deform_bindings.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/methods.h"
#include "lapis/mesh_deform/metrics.h"
#include "lapis/mesh_deform/salient_deformer.h"
#include "lapis/mesh_deform/selection_io.h"

namespace lapis::python {
namespace {

using namespace lapis::mesh_deform;
using namespace pybind11::literals;

// Readable settings: each struct prints its fields, so help() and the REPL show the defaults.
template <class T>
void def_repr(py::class_<T>& c, const char* name) {
  c.def("__repr__", [name](const py::object& self) {
    std::string s = std::string(name) + "(";
    bool first = true;
    for (const py::handle& key : self.attr("_fields")) {
      s += (first ? "" : ", ") + key.cast<std::string>() + "=" + py::repr(self.attr(key)).cast<std::string>();
      first = false;
    }
    return s + ")";
  });
}

// Binds fields by name and records the names in _fields (what Deformer's keyword options and
// __repr__ walk).
template <class T>
struct Fields {
  py::class_<T> cls;
  py::list names;
  Fields(py::module_& m, const char* name, const char* doc) : cls(m, name, doc) {
    cls.def(py::init<>());
    cls.def(py::self == py::self);
  }
  template <class M>
  Fields& field(const char* name, M T::*member, const char* doc) {
    cls.def_readwrite(name, member, doc);
    names.append(name);
    return *this;
  }
  void done(const char* name) {
    cls.attr("_fields") = py::tuple(names);
    def_repr(cls, name);
  }
};

void bind_enums(py::module_& m) {
  py::enum_<Method> method(m, "Method", "The deformation methods of the registry (lapis.methods()).");
  for (const MethodInfo& info : methods()) method.value(info.name, info.method, info.label);
  py::enum_<LaplacianWeights>(m, "LaplacianWeights", "Thesis §2.3's weightings.")
      .value(to_string(LaplacianWeights::Cotangent), LaplacianWeights::Cotangent)
      .value(to_string(LaplacianWeights::Uniform), LaplacianWeights::Uniform);
  py::enum_<LaplacianDomain>(m, "LaplacianDomain", "Where the edge method's Laplacian vectors live.")
      .value(to_string(LaplacianDomain::Edges), LaplacianDomain::Edges)
      .value(to_string(LaplacianDomain::Vertices), LaplacianDomain::Vertices);
  py::enum_<CellTransform> t(m, "CellTransform", "What the edge method's T_i may do to its cell (Eq. 7-8).");
  for (CellTransform v :
       {CellTransform::Rotation, CellTransform::IsotropicScale, CellTransform::AnisotropicScale, CellTransform::Full})
    t.value(to_string(v), v);
  py::enum_<ScaleFrame>(m, "ScaleFrame", "The axes of the edge method's anisotropic scale.")
      .value(to_string(ScaleFrame::World), ScaleFrame::World)
      .value(to_string(ScaleFrame::RestPrincipal), ScaleFrame::RestPrincipal);
  py::enum_<IsolineSolve>(m, "IsolineSolve", "Eq. 10 (reduced) or Eq. 6 (full).")
      .value(to_string(IsolineSolve::Reduced), IsolineSolve::Reduced)
      .value(to_string(IsolineSolve::Full), IsolineSolve::Full);
  py::enum_<IsolineFit> fit(m, "IsolineFit", "How an isoline's transformation is fitted (Eq. 8).");
  for (IsolineFit v : {IsolineFit::Rotation, IsolineFit::Similarity, IsolineFit::Paper}) fit.value(to_string(v), v);
  py::enum_<FeatureWeight>(m, "FeatureWeight", "w_i of the salient method's Eq. 2.")
      .value("size", FeatureWeight::Size)
      .value("uniform", FeatureWeight::Uniform);
  py::enum_<ColdStart>(m, "ColdStart", "How ARAP, edge and salient start a frame without a previous result.")
      .value("handle_rotations", ColdStart::HandleRotations)
      .value("identity", ColdStart::Identity);
  py::enum_<FeatureMerge>(m, "FeatureMerge", "How user features combine with detected ones.")
      .value("replace", FeatureMerge::Replace)
      .value("union", FeatureMerge::Union);
}

void bind_settings(py::module_& m) {
  Fields<EdgeLaplacianOptions>(m, "EdgeLaplacianOptions", "Options of the edge method (Wang et al.).")
      .field("domain", &EdgeLaplacianOptions::domain, "edges (§3.3) or vertices (the §4 baseline)")
      .field("weights", &EdgeLaplacianOptions::weights, "uniform (§3.1) or cotan")
      .field("transform", &EdgeLaplacianOptions::transform, "anisotropic (§3.4, T = S R1) by default")
      .field("frame", &EdgeLaplacianOptions::frame, "world (§3.4) or principal rest axes")
      .field("iterations", &EdgeLaplacianOptions::iterations, "T-updates per deform() (§4: three to four)")
      .field("tolerance", &EdgeLaplacianOptions::tolerance, "stop once no vertex moves more (x bbox diagonal)")
      .field("warm_start", &EdgeLaplacianOptions::warm_start, "start a frame from the last one's transforms")
      .field("cold_start", &EdgeLaplacianOptions::cold_start, "ColdStart of a frame without a previous result")
      .field("soft_handles", &EdgeLaplacianOptions::soft_handles, "Eq. 6 penalized handles instead of hard ones")
      .field("handle_weight", &EdgeLaplacianOptions::handle_weight, "Eq. 6's weight of soft handles")
      .done("EdgeLaplacianOptions");
  Fields<HandleFieldOptions>(m, "HandleFieldOptions", "Harmonic handle fields of the isolines method.")
      .field("point_handle_radius", &HandleFieldOptions::point_handle_radius, "disc radius (x bbox diagonal)")
      .done("HandleFieldOptions");
  Fields<IsolinesOptions>(m, "IsolinesOptions", "Options of the isolines method (Au et al.).")
      .field("isolines", &IsolinesOptions::isolines, "n_iso per handle (§4.1)")
      .field("solve", &IsolinesOptions::solve, "reduced (Eq. 10) or full (Eq. 6)")
      .field("fit", &IsolinesOptions::fit, "rotation, similarity or paper (Eq. 9)")
      .field("omega", &IsolinesOptions::omega, "§3 Eq. 2: soft handle weight")
      .field("beta", &IsolinesOptions::beta, "§4.2 isoline smoothness")
      .field("triangle_budget", &IsolinesOptions::triangle_budget, "n_tri of §4.3 (0: 30 per isoline)")
      .field("min_triangles_per_isoline", &IsolinesOptions::min_triangles_per_isoline,
             "so that a sparse isoline still has >= 3 non-coplanar normals")
      .field("max_iterations", &IsolinesOptions::max_iterations, "per deform()")
      .field("tolerance", &IsolinesOptions::tolerance, "relative step size that stops the iteration")
      .field("anderson_depth", &IsolinesOptions::anderson_depth, "Anderson acceleration depth (0: off)")
      .field("large_rotations", &IsolinesOptions::large_rotations, "guide isolines past guide_angle")
      .field("guide_angle", &IsolinesOptions::guide_angle, "radians")
      .field("guide_weight", &IsolinesOptions::guide_weight,
             "of the large-rotation guides, relative to the Laplacian part's mean diagonal")
      .field("fields", &IsolinesOptions::fields, "HandleFieldOptions")
      .done("IsolinesOptions");
  Fields<HeatKernelOptions>(m, "HeatKernelOptions", "Heat kernel signature of the salient detection.")
      .field("eigenpairs", &HeatKernelOptions::eigenpairs, "k")
      .field("time_scales", &HeatKernelOptions::time_scales, "log-spaced times")
      .field("truncation", &HeatKernelOptions::truncation, "weight of the last eigenpair kept at t_min")
      .done("HeatKernelOptions");
  Fields<geometry::BilateralOptions>(m, "BilateralOptions", "Bilateral mesh denoising (Fleishman et al. 2003).")
      .field("iterations", &geometry::BilateralOptions::iterations, "passes of the filter")
      .field("sigma_c", &geometry::BilateralOptions::sigma_c, "spatial falloff; 0: the mean edge length")
      .done("BilateralOptions");
  Fields<FeatureOptions>(m, "FeatureOptions", "Salient feature detection (Zhao et al. §3.1).")
      .field("denoise", &FeatureOptions::denoise, "BilateralOptions of the copy the spectrum is computed on")
      .field("hks", &FeatureOptions::hks, "HeatKernelOptions")
      .field("max_cluster_fraction", &FeatureOptions::max_cluster_fraction, "Step 2's N_max / #V")
      .field("min_cluster_saliency", &FeatureOptions::min_cluster_saliency, "Step 2's s_min")
      .field("aggregate_saliency", &FeatureOptions::aggregate_saliency, "Step 3's s_agg")
      .field("stop_seeding_early", &FeatureOptions::stop_seeding_early,
             "skip seeds below aggregate_saliency (same features, faster)")
      .done("FeatureOptions");
  Fields<SalientOptions>(m, "SalientOptions", "Options of the salient method (Zhao et al.).")
      .field("alpha", &SalientOptions::alpha, "Eq. 10: weight of E_ldp")
      .field("beta", &SalientOptions::beta, "Eq. 10: weight of the soft handles")
      .field("gamma", &SalientOptions::gamma, "Eq. 10: weight of E_disc")
      .field("lambda_", &SalientOptions::lambda, "Eq. 10: weight of E_vibr")
      .field("iterations", &SalientOptions::iterations, "per deform() (§5: three to five)")
      .field("feature_weight", &SalientOptions::feature_weight, "size or uniform")
      .field("feature_weight_scale", &SalientOptions::feature_weight_scale,
             "multiplies every w_i (rigidity against the rest)")
      .field("subspace_vertices", &SalientOptions::subspace_vertices, "of the enclosing lattice")
      .field("detect_features", &SalientOptions::detect_features, "§3.1 detection")
      .field("detection", &SalientOptions::detection, "FeatureOptions")
      .field("user_features", &SalientOptions::user_features, "replace or union")
      .field("warm_start", &SalientOptions::warm_start, "start a frame from the last rotations")
      .field("cold_start", &SalientOptions::cold_start, "ColdStart of a frame without a previous result")
      .done("SalientOptions");
  Fields<MethodSettings>(m, "MethodSettings", "A method and its options, as make_deformer() takes them.")
      .field("method", &MethodSettings::method, "Method")
      .field("weights", &MethodSettings::weights, "naive and implicit: cotan or uniform (§2.3)")
      .field("scale_features", &MethodSettings::scale_features, "implicit: Eq. 2.11 instead of Eq. 2.10")
      .field("arap_iterations", &MethodSettings::arap_iterations, "arap: iterations per frame")
      .field("edge", &MethodSettings::edge, "EdgeLaplacianOptions")
      .field("salient", &MethodSettings::salient, "SalientOptions")
      .field("isolines", &MethodSettings::isolines, "IsolinesOptions")
      .done("MethodSettings");
}

HandleTransforms to_transforms(const py::handle& regions, const py::handle& points) {
  HandleTransforms t;
  py::array r = py::isinstance<py::array>(regions) ? py::reinterpret_borrow<py::array>(regions)
                                                   : py::array_t<double>::ensure(regions);
  if (r.dtype().kind() != 'f' || r.itemsize() != 8)
    throw py::type_error("regions must be float64, not " + py::str(r.dtype()).cast<std::string>());
  if (r.ndim() != 3 || r.shape(1) != 4 || r.shape(2) != 4)
    throw py::value_error("regions must have shape (#region handles, 4, 4), not " + shape_text(r));
  const auto rows = to_dense(r.reshape({r.shape(0) * 4, py::ssize_t{4}}), "regions", 4);
  for (Eigen::Index k = 0; k < r.shape(0); ++k) t.regions.push_back(rows.middleRows(4 * k, 4));
  const auto p = to_dense(points, "points", 3);
  for (Eigen::Index k = 0; k < p.rows(); ++k) t.points.push_back(p.row(k).transpose());
  return t;
}

py::dict summary(const Summary& s) {
  return py::dict("mean"_a = s.mean, "max"_a = s.max, "p95"_a = s.p95, "count"_a = s.count);
}

// The method's own report, by method.
py::dict report(const Deformer& d) {
  py::dict r("method"_a = d.name());
  if (const auto* i = dynamic_cast<const ImplicitLaplacianDeformer*>(&d)) {
    const ImplicitReport& x = i->report();
    r["free_vertices"] = x.free_vertices, r["degenerate_vertices"] = x.degenerate_vertices;
    r["setup_ms"] = x.setup_ms, r["frame_ms"] = x.frame_ms;
  } else if (const auto* e = dynamic_cast<const EdgeLaplacianDeformer*>(&d)) {
    const EdgeLaplacianReport& x = e->report();
    r["rows"] = x.rows, r["unknowns"] = x.unknowns, r["iterations"] = x.iterations, r["last_move"] = x.last_move;
    r["setup_ms"] = x.setup_ms, r["frame_ms"] = x.frame_ms;
  } else if (const auto* s = dynamic_cast<const SalientDeformer*>(&d)) {
    const SalientReport& x = s->report();
    r["features"] = x.features, r["subspace_vertices"] = x.subspace_vertices, r["iterations"] = x.iterations;
    r["precompute_ms"] = x.precompute_ms, r["frame_ms"] = x.frame_ms;
  } else if (const auto* iso = dynamic_cast<const IsolinesDeformer*>(&d)) {
    const IsolinesReport& x = iso->report();
    r["handles"] = x.handles, r["unknowns"] = x.unknowns, r["iterations"] = x.iterations;
    r["setup_ms"] = x.setup_ms, r["frame_ms"] = x.frame_ms;
  }
  return r;
}

py::dict drag_dict(Drag&& drag) {
  py::list regions, frames;
  for (auto& h : drag.selection.region_handles) regions.append(to_numpy(std::move(h)));
  for (const HandleTransforms& t : drag.frames) {
    Eigen::MatrixXd R(4 * t.regions.size(), 4);
    for (size_t k = 0; k < t.regions.size(); ++k) R.middleRows(4 * static_cast<Eigen::Index>(k), 4) = t.regions[k];
    Eigen::Matrix<double, Eigen::Dynamic, 4, Eigen::RowMajor> Rr = R;
    py::array regions_T =
        to_numpy(std::move(Rr)).reshape({static_cast<py::ssize_t>(t.regions.size()), py::ssize_t{4}, py::ssize_t{4}});
    geometry::Vertices P(static_cast<Eigen::Index>(t.points.size()), 3);
    for (size_t k = 0; k < t.points.size(); ++k) P.row(static_cast<Eigen::Index>(k)) = t.points[k].transpose();
    frames.append(py::make_tuple(regions_T, to_numpy(std::move(P))));
  }
  return py::dict("regions"_a = regions, "points"_a = to_numpy(std::move(drag.selection.point_handles)),
                  "frames"_a = frames);
}

void bind_deformer(py::module_& m) {
  py::class_<Deformer> deformer(m, "_Deformer", "make_deformer() behind lapis.Deformer.");
  deformer
      .def(py::init([](const py::handle& V, const py::handle& F, const MethodSettings& settings) {
             TriMesh mesh = to_mesh(V, F);
             py::gil_scoped_release release;
             return make_deformer(std::move(mesh), settings).release();
           }),
           "V"_a, "F"_a, "settings"_a)
      .def(
          "set_selection",
          [](Deformer& d, const py::handle& roi, const py::handle& regions, const py::handle& points) {
            d.set_selection(to_selection(roi, regions, points));
          },
          "roi"_a, "regions"_a, "points"_a)
      .def("precompute", &Deformer::precompute, py::call_guard<py::gil_scoped_release>())
      .def(
          "deform",
          [](Deformer& d, const py::handle& regions, const py::handle& points) {
            const HandleTransforms t = to_transforms(regions, points);
            Vertices out;
            {
              py::gil_scoped_release release;
              out = d.deform(t);
            }
            return to_numpy(std::move(out));
          },
          "regions"_a, "points"_a)
      .def_property_readonly("name", &Deformer::name)
      .def_property_readonly("dirty", &Deformer::dirty)
      .def("report", &report);
  bind_method_members(deformer);
}

}  // namespace

Selection to_selection(const py::handle& roi, const py::handle& regions, const py::handle& points) {
  Selection s;
  s.roi = to_indices(roi, "roi");
  for (const py::handle& h : regions) s.region_handles.push_back(to_indices(h, "regions[i]"));
  s.point_handles = to_indices(points, "points");
  return s;
}

void bind_deform(py::module_& m) {
  bind_enums(m);
  bind_settings(m);
  bind_deformer(m);
  bind_transfer(m);
  m.def(
      "methods",
      [] {
        py::list names;
        for (const MethodInfo& info : methods()) names.append(info.name);
        return names;
      },
      "The deformation methods' names, in menu order: what Deformer(method=...) accepts.");
  m.def(
      "distortion",
      [](const py::handle& V, const py::handle& F, const py::handle& deformed) {
        const TriMesh rest = to_mesh(V, F);
        const Vertices W = to_vertices(deformed, "deformed");
        Distortion q;
        {
          py::gil_scoped_release release;
          q = distortion(rest, W);
        }
        return py::dict("edge_length"_a = summary(q.edge_length), "laplacian_length"_a = summary(q.laplacian_length),
                        "angle"_a = summary(q.angle), "arap_energy"_a = q.arap_energy);
      },
      "V"_a, "F"_a, "deformed"_a,
      R"(Distortion of `deformed` (#V, 3) against the rest mesh (V, F): a dict of edge_length,
laplacian_length and angle summaries (mean, max, p95, count) and the scale-free arap_energy.)");
  m.def(
      "read_roi", [](const std::filesystem::path& path) { return to_numpy(read_roi(path)); }, "path"_a,
      "An ROI file of `lapis deform` (JSON array or whitespace-separated indices) as an int32 array.");
  m.def(
      "read_handles", [](const std::filesystem::path& path) { return drag_dict(read_handles(path)); }, "path"_a,
      R"(A handles file of `lapis deform`: {'regions': [int32 arrays], 'points': int32 array,
'frames': [(region transforms (#regions, 4, 4), point translations (#points, 3)), ...]}.)");
}

}  // namespace lapis::python
