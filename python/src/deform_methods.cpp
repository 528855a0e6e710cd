// What a method has beyond precompute() and deform(): the salient method's features,
// saliency and solid subspace (Zhao et al. §3), the isolines method's harmonic fields and
// rigidity (Au et al. §4.1), and deformation transfer by handle correspondence (Au et al. §6).
#include <pybind11/stl.h>

#include <string>
#include <utility>
#include <vector>

#include "arrays.h"
#include "deform_bindings.h"
#include "lapis/core/error.h"
#include "lapis/mesh_deform/deformation_transfer.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/salient_deformer.h"

namespace lapis::python {
namespace {

using namespace lapis::mesh_deform;
using namespace pybind11::literals;

// The deformer as method D, or a UsageError naming the member and the methods that have it.
template <class D>
D& as_method(Deformer& d, const char* member, const char* method) {
  if (auto* x = dynamic_cast<D*>(&d)) return *x;
  throw UsageError(std::string("lapis.Deformer.") + member + ": only the " + method +
                   " method has it; this deformer's method is '" + d.name() + "'");
}

void bind_salient_members(py::class_<Deformer>& c) {
  c.def(
       "set_features",
       [](Deformer& d, const py::handle& features) {
         std::vector<Feature> out;
         for (const py::handle& f : features) out.push_back(to_indices(f, "features[i]"));
         as_method<SalientDeformer>(d, "set_features()", "salient").set_features(std::move(out));
       },
       "features"_a)
      .def(
          "set_subspace",
          [](Deformer& d, const py::handle& V, const py::handle& T) {
            geometry::TetMesh tets{to_vertices(V, "V"), to_tets(T, "T")};
            as_method<SalientDeformer>(d, "set_subspace()", "salient").set_subspace(std::move(tets));
          },
          "V"_a, "T"_a)
      .def_property_readonly("features",
                             [](Deformer& d) {
                               py::list out;
                               for (Feature f : as_method<SalientDeformer>(d, "features", "salient").features())
                                 out.append(to_numpy(std::move(f)));
                               return out;
                             })
      .def_property_readonly("saliency",
                             [](Deformer& d) {
                               Eigen::VectorXd s = as_method<SalientDeformer>(d, "saliency", "salient").saliency();
                               return to_numpy(std::move(s));
                             })
      .def_property_readonly("subspace", [](Deformer& d) {
        geometry::TetMesh t = as_method<SalientDeformer>(d, "subspace", "salient").subspace();
        return py::make_tuple(to_numpy(std::move(t.V)), to_numpy(std::move(t.T)));
      });
}

void bind_isolines_members(py::class_<Deformer>& c) {
  c.def_property_readonly("fields", [](Deformer& d) {
     Eigen::MatrixXd phi = as_method<IsolinesDeformer>(d, "fields", "isolines").fields();
     return to_numpy(std::move(phi));
   }).def_property_readonly("rigidity", [](Deformer& d) {
    return to_numpy(as_method<IsolinesDeformer>(d, "rigidity", "isolines").rigidity());
  });
}

py::dict transfer_report(const TransferReport& r) {
  return py::dict("handles"_a = r.handles, "unknowns"_a = r.unknowns, "eq11_residual"_a = r.eq11_residual,
                  "eq12_residual"_a = r.eq12_residual, "pinned"_a = r.pinned, "setup_ms"_a = r.setup_ms);
}

}  // namespace

void bind_method_members(py::class_<Deformer>& deformer) {
  bind_salient_members(deformer);
  bind_isolines_members(deformer);
}

void bind_transfer(py::module_& m) {
  py::class_<DeformationTransfer>(m, "_DeformationTransfer", "DeformationTransfer behind lapis.DeformationTransfer.")
      .def(py::init([](const py::handle& sV, const py::handle& sF, const py::tuple& sh, const py::handle& tV,
                       const py::handle& tF, const py::tuple& th, int isolines, double point_handle_radius) {
             const TriMesh source = to_mesh(sV, sF), target = to_mesh(tV, tF);
             const Selection s = to_selection(sh[0], sh[1], sh[2]), t = to_selection(th[0], th[1], th[2]);
             TransferOptions o;
             o.isolines = isolines;
             o.fields.point_handle_radius = point_handle_radius;
             py::gil_scoped_release release;
             return new DeformationTransfer(source, s, target, t, o);
           }),
           "source_V"_a, "source_F"_a, "source_handles"_a, "target_V"_a, "target_F"_a, "target_handles"_a,
           "isolines"_a = TransferOptions{}.isolines,
           "point_handle_radius"_a = TransferOptions{}.fields.point_handle_radius)
      .def(
          "transfer",
          [](DeformationTransfer& x, const py::handle& deformed) {
            const Vertices W = to_vertices(deformed, "source_deformed");
            Vertices out;
            {
              py::gil_scoped_release release;
              out = x.transfer(W);
            }
            return to_numpy(std::move(out));
          },
          "source_deformed"_a)
      .def("report", [](const DeformationTransfer& x) { return transfer_report(x.report()); });
}

}  // namespace lapis::python
