// Watertight seams (thesis §3.3.1, after Yu et al. 2004): once the source boundary lies on
// the target boundary, remove one band of target triangles next to each target merging loop
// and re-triangulate the gap between the deformed source loop and the band's inner loop;
// then smooth the seam band with a few umbrella-operator iterations (Taubin 1995 / [101]).
#pragma once

#include <vector>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

struct ZipResult {
  TriMesh mesh;                    // target part first, then the source
  std::vector<int> target_map;     // #V_target: merged index, -1 for vertices removed with the band
  std::vector<int> source_map;     // #V_source: merged index
  std::vector<int> strip_faces;    // merged faces of the re-triangulated gaps
  std::vector<int> seam_vertices;  // merged vertices on the strips (both sides), ascending
};

// source  the deformed source (same connectivity as the one pairs were made on). Throws
// InvalidArgument "mesh_merge::zip_seams(): ..." when removing a band does not leave exactly
// one inner loop for each pair (a target too coarse or too thin next to its boundary).
ZipResult zip_seams(const TriMesh& target, const TriMesh& source, const std::vector<BoundaryCorrespondence>& pairs);

// Seam band: the vertices within `rings` edges of the seam vertices (the seam itself for 0).
std::vector<int> seam_band(const TriMesh& mesh, const std::vector<int>& seam_vertices, int rings);

// `iterations` Jacobi steps of the uniform umbrella operator v ← v + λ (mean of neighbours − v)
// on the listed vertices only; every other vertex stays where it is. Throws InvalidArgument
// "mesh_merge::umbrella_smooth(): ..." for λ outside (0, 1], negative iterations or an index
// out of range.
void umbrella_smooth(TriMesh& mesh, const std::vector<int>& vertices, int iterations, double lambda);

// Unfolds the seam: while some edge of strip_faces folds (its two faces turn by more than
// geometry::kFoldedDihedralDeg), one umbrella step moves the vertices of the folded edges'
// faces that are in `movable`; at most max_rounds steps. Returns the folded edges left.
int unfold_seam(TriMesh& mesh, const std::vector<int>& strip_faces, const std::vector<int>& movable,
                int max_rounds = 50, double lambda = 0.5);

}  // namespace lapis::mesh_merge
