// Watertight seams (thesis §3.3.1, after Yu et al. 2004): once the source boundary lies on
// the target boundary, remove one band of target triangles next to each target merging loop
// and re-triangulate the gap between the deformed source loop and the band's inner loop;
// then smooth the seam band with a few umbrella-operator iterations (Taubin 1995 / [101]).
// Where that band is not an annulus (the loop passes within one triangle of itself or of a
// thin part, and removing the band would cut the target apart), the pair is zipped without
// removing anything: the two loops are merged into one polyline and the triangles on it split.
#pragma once

#include <vector>

#include "lapis/mesh_merge/boundary.h"

namespace lapis::mesh_merge {

struct ZipResult {
  TriMesh mesh;                    // target part first, then the source
  std::vector<int> target_map;     // #V_target: merged index, -1 for vertices removed with a band
  std::vector<int> source_map;     // #V_source: merged index (a target vertex's where they were merged)
  std::vector<int> strip_faces;    // merged faces of the re-triangulated gaps (zipped without a band:
                                   // the faces on the merged loop, both sides)
  std::vector<int> seam_vertices;  // merged vertices on the strips (both sides), ascending
};

// source  the deformed source (same connectivity as the one pairs were made on). A pair is
// zipped without a band only when its source loop lies on the target loop (target_edge and
// target_t given, as the merge's boundary conditions make it); a source point within a fifth
// of a target edge of the edge's end becomes that target vertex. Throws InvalidArgument
// "mesh_merge::zip_seams(): ..." for a band that is not an annulus on a pair without
// target_edge (a transition region's rim), and for two target loops within one triangle of
// each other.
ZipResult zip_seams(const TriMesh& target, const TriMesh& source, const std::vector<BoundaryCorrespondence>& pairs);

// Seam band: the vertices within `rings` edges of the seam vertices (the seam itself for 0).
std::vector<int> seam_band(const TriMesh& mesh, const std::vector<int>& seam_vertices, int rings);

// `iterations` Jacobi steps of the uniform umbrella operator v ← v + λ (mean of neighbours − v)
// on the listed vertices only; every other vertex stays where it is. Throws InvalidArgument
// "mesh_merge::umbrella_smooth(): ..." for λ outside (0, 1], negative iterations or an index
// out of range.
void umbrella_smooth(TriMesh& mesh, const std::vector<int>& vertices, int iterations, double lambda);

// Unfolds the seam: a folded edge of strip_faces (its two faces turn by more than
// geometry::kFoldedDihedralDeg) between two strip faces is flipped where the other diagonal
// turns them and their neighbours less (the faces keep their indices); then, while some strip
// edge folds, one umbrella step moves the vertices of the folded edges' faces that are in
// `movable`, at most max_rounds steps; flips and steps twice. Returns the folded edges left.
int unfold_seam(TriMesh& mesh, const std::vector<int>& strip_faces, const std::vector<int>& movable,
                int max_rounds = 50, double lambda = 0.5);

// Flips an edge between two strip faces where the other diagonal makes the pair's smallest
// angle larger by more than rounding (a tie stays), unless the pair or a neighbour across its
// outer edges folds before or after (folds are unfold_seam()'s). The faces keep their indices.
// Works on the strip's faces and those touching them only. Returns the flips.
int flip_thin_diagonals(TriMesh& mesh, const std::vector<int>& strip_faces);

}  // namespace lapis::mesh_merge
