#include "lapis/mesh_deform/methods.h"

#include "lapis/mesh_deform/arap.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/implicit_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/naive_laplacian.h"
#include "lapis/mesh_deform/salient_deformer.h"

namespace lapis::mesh_deform {

const std::vector<MethodInfo>& methods() {
  static const std::vector<MethodInfo> list = {
      {Method::Naive, "naive", "naive Laplacian (Eq. 2.1)"},
      {Method::Implicit, "implicit", "implicit Laplacian (thesis ch. 2)"},
      {Method::Arap, "arap", "ARAP (Sorkine & Alexa)"},
      {Method::Edge, "edge", "edge-based Laplacian (Wang et al.)"},
      {Method::Salient, "salient", "salient features, solid subspace (Zhao et al.)"},
      {Method::Isolines, "isolines", "handle-aware isolines (Au et al.)"},
  };
  return list;
}

const MethodInfo& method_info(Method m) {
  for (const auto& info : methods())
    if (info.method == m) return info;
  throw InvalidArgument("mesh_deform::method_info(): unknown method");
}

std::string method_names(const char* separator) {
  std::string known;
  for (const auto& info : methods()) {
    if (!known.empty()) known += separator;
    known += info.name;
  }
  return known;
}

Method method_from_name(const std::string& name) {
  for (const auto& info : methods())
    if (name == info.name) return info.method;
  throw InvalidArgument("mesh_deform::method_from_name(): unknown method '" + name + "', expected one of " +
                        method_names());
}

std::unique_ptr<Deformer> make_deformer(TriMesh mesh, const MethodSettings& s) {
  switch (s.method) {
    case Method::Naive:
      return std::make_unique<NaiveLaplacianDeformer>(std::move(mesh), NaiveOptions{s.weights});
    case Method::Implicit: {
      ImplicitOptions o;
      o.weights = s.weights;
      if (s.scale_features) o.shearing = ShearingRemoval::ScaleFeatures;
      return std::make_unique<ImplicitLaplacianDeformer>(std::move(mesh), o);
    }
    case Method::Arap: {
      if (s.arap_iterations < 1)
        throw InvalidArgument("mesh_deform::make_deformer(): arap_iterations = " + std::to_string(s.arap_iterations) +
                              ", expected >= 1");
      ArapOptions o;
      o.max_iterations = s.arap_iterations;
      return std::make_unique<ArapDeformer>(std::move(mesh), o);
    }
    case Method::Edge:
      return std::make_unique<EdgeLaplacianDeformer>(std::move(mesh), s.edge);
    case Method::Salient:
      return std::make_unique<SalientDeformer>(std::move(mesh), s.salient);
    case Method::Isolines:
      return std::make_unique<IsolinesDeformer>(std::move(mesh), s.isolines);
  }
  throw InvalidArgument("mesh_deform::make_deformer(): unknown method");
}

}  // namespace lapis::mesh_deform
