// The regions file of an optimal-boundary merge (thesis §3.4): the source's rough region Ω0 and
// feature region Ωf and the target's region Ω1, each as faces or as vertices (a face belongs to
// a vertex-given region when all three of its corners do), 0-based:
//   {"rough": {"faces": [...]}, "feature": {"vertices": [...]}, "target": {"faces": [...]}}
// "rough" and "target" may be left out: every face of that mesh. `lapis merge --mode optimal`
// reads it and the merge app writes it.
#pragma once

#include <filesystem>

#include "lapis/mesh_merge/optimal_boundary.h"

namespace lapis::mesh_merge {

// Throws IoError "mesh_merge::read_regions_file(): <path>: ..." for a missing file or invalid
// JSON, and InvalidArgument (same prefix, naming the JSON element) for a wrong structure, a
// region with both or neither of "faces" and "vertices", or an index that is not an integer or
// (vertices) out of range for its mesh. Face indices are range-checked by BoundaryOptimizer.
BoundaryRegions read_regions_file(const std::filesystem::path& path, const TriMesh& source, const TriMesh& target);

// Writes face lists; atomic; throws IoError.
void write_regions_file(const std::filesystem::path& path, const BoundaryRegions& regions);

}  // namespace lapis::mesh_merge
