// How good a merge is (the quality metrics used by the tests, the CLI report and the
// benchmark): is the seam valid and watertight, did the target stay put away from the seam,
// is the seam as smooth as the target itself, and did the source keep its details.
#pragma once

#include <vector>

#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/merge.h"

namespace lapis::mesh_merge {

struct SeamQuality {
  int seam_boundary_edges = 0;  // boundary edges with both ends on the seam: 0 when watertight
  int non_manifold_edges = 0;   // in the whole merged mesh
  int non_manifold_vertices = 0;
  int degenerate_faces = 0;
  double min_strip_angle_deg = 0;  // smallest corner angle of the zipped strips
  double max_target_displacement =
      0;                              // over target vertices outside the smoothed and transition bands, / bbox diagonal
  double seam_dihedral_mean_deg = 0;  // normal deviation across strip edges
  double seam_dihedral_max_deg = 0;
  // Strip edges whose two faces turn by more than geometry::kFoldedDihedralDeg: a triangle
  // facing against the surface beside it (a spike or a notch), which no smooth seam has.
  int folded_seam_edges = 0;
  // Folded strip edges on an edge where the target itself folds (a spike of a scan next to its
  // loop): the target's, not the seam's, so not in folded_seam_edges.
  int inherited_folds = 0;
  double target_dihedral_mean_deg = 0;  // the target's own interior edges, for comparison
  double target_dihedral_p95_deg = 0;
  bool valid() const {
    return seam_boundary_edges == 0 && non_manifold_edges == 0 && non_manifold_vertices == 0 && degenerate_faces == 0 &&
           folded_seam_edges == 0;
  }
};

struct DetailPreservation {
  // ‖L x′ − T(δ)‖ / ‖T(δ)‖ over the source's interior vertices: L the rest cotangent Laplacian,
  // T_i the similarity best fitting vertex i's 1-ring from rest to merged (the deformation the
  // details should have followed); normalized by ‖T(δ)‖ so the figure is scale invariant.
  double laplacian_residual = 0;
  // Source interior after the best similarity alignment to its original (Umeyama): largest and
  // mean vertex distance (an upper bound of the Hausdorff distance), / merged source bbox diagonal.
  double max_distance = 0;
  double mean_distance = 0;
  // The angle of that similarity's rotation, in degrees: how far the merge turned the source
  // from where it was given (placed). Over 90° it landed the other way round (face-down: a key
  // correspondence on the wrong side of the loop, suggest_key.h).
  double turn_deg = 0;
};

// target  the target as given to merge(); r its result.
SeamQuality seam_quality(const TriMesh& target, const MergeResult& r);

// source  the source as given to merge(); r its result.
DetailPreservation detail_preservation(const TriMesh& source, const MergeResult& r);

// How well a part of the source kept its shape through the merge: the largest distance of its
// merged vertices from the best similar copy (Umeyama) of the part as given, over the merged
// part's bounding-box diagonal. 0 for a part moved by one similarity. vertices: source vertices
// as given, each kept by the merge (r.source_map >= 0), at least 3; throws InvalidArgument
// "mesh_merge::feature_distortion(): ..." otherwise.
double feature_distortion(const TriMesh& source, const MergeResult& r, const std::vector<int>& vertices);

// Angles (degrees) between the normals of the two faces of each interior edge of mesh, for the
// listed faces' edges only when faces is non-empty.
std::vector<double> dihedral_deviation_deg(const TriMesh& mesh, const std::vector<int>& faces = {});

double bbox_diagonal(const Vertices& V);

}  // namespace lapis::mesh_merge
