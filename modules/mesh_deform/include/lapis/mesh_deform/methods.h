// Every deformer of the module behind one list and one factory, so the CLI and the apps offer
// the same methods with the same settings (and a method added later appears in both). The
// settings are those a user picks; each method's options struct keeps the papers' defaults.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "lapis/mesh_deform/deformer.h"
#include "lapis/mesh_deform/edge_laplacian.h"
#include "lapis/mesh_deform/isolines_deformer.h"
#include "lapis/mesh_deform/laplacian_weights.h"
#include "lapis/mesh_deform/salient_deformer.h"

namespace lapis::mesh_deform {

enum class Method { Naive, Implicit, Arap, Edge, Salient, Isolines };

struct MethodInfo {
  Method method;
  const char* name;   // command-line name: naive, implicit, arap, edge, isolines
  const char* label;  // menu text
};

// In menu order.
const std::vector<MethodInfo>& methods();
const MethodInfo& method_info(Method m);
// Throws InvalidArgument naming the known methods.
Method method_from_name(const std::string& name);
// The command-line names in menu order, "naive, implicit, ...", for messages; with separator
// "|", "naive|implicit|...", for usage lines.
std::string method_names(const char* separator = ", ");

struct MethodSettings {
  Method method = Method::Implicit;
  LaplacianWeights weights = LaplacianWeights::Cotangent;  // naive and implicit (§2.3)
  bool scale_features = false;                             // implicit: Eq. 2.11 (R_i S_i δ_i) instead of Eq. 2.10
  int arap_iterations = 10;   // ARAP iterations per frame (Sorkine & Alexa: 2-3 while dragging)
  EdgeLaplacianOptions edge;  // the edge-based method (Wang et al.), its own weights and iterations
  SalientOptions salient;     // salient features in a solid subspace (Zhao et al.)
  IsolinesOptions isolines;   // the handle-aware isolines reduced model (Au et al.)

  bool operator==(const MethodSettings&) const = default;
};

// A deformer of the chosen method with these settings. Throws InvalidArgument for
// arap_iterations < 1 and for edge, salient or isolines options that their set_options() refuses.
std::unique_ptr<Deformer> make_deformer(TriMesh mesh, const MethodSettings& settings);

}  // namespace lapis::mesh_deform
