// The two Laplacian weightings of thesis §2.3: uniform (Lipman et al., Sorkine et al.) and
// cotangent (Meyer et al., Desbrun et al.); §2.4.3 explains why cotangent is the default.
#pragma once

namespace lapis::mesh_deform {

enum class LaplacianWeights { Cotangent, Uniform };

const char* to_string(LaplacianWeights w);

}  // namespace lapis::mesh_deform
