// The parts of `lapis merge`'s JSON report that every mode shares: the seam's validity and
// smoothness, and how well the source's details survived.
#pragma once

#include <nlohmann/json.hpp>

#include "args.h"
#include "lapis/mesh_merge/metrics.h"

namespace lapis::cli {

inline nlohmann::json seam_json(const mesh_merge::SeamQuality& q) {
  return {{"valid", q.valid()},
          {"boundary_edges", q.seam_boundary_edges},
          {"non_manifold_edges", q.non_manifold_edges},
          {"non_manifold_vertices", q.non_manifold_vertices},
          {"degenerate_faces", q.degenerate_faces},
          {"min_strip_angle_deg", q.min_strip_angle_deg},
          {"max_target_displacement", q.max_target_displacement},
          {"dihedral_mean_deg", q.seam_dihedral_mean_deg},
          {"dihedral_max_deg", q.seam_dihedral_max_deg},
          {"folded_edges", q.folded_seam_edges},
          {"inherited_folds", q.inherited_folds},
          {"target_dihedral_mean_deg", q.target_dihedral_mean_deg},
          {"target_dihedral_p95_deg", q.target_dihedral_p95_deg}};
}

inline nlohmann::json detail_json(const mesh_merge::DetailPreservation& d) {
  return {{"laplacian_residual", d.laplacian_residual},
          {"max_distance", d.max_distance},
          {"mean_distance", d.mean_distance},
          {"turn_deg", d.turn_deg}};
}

// Prints why a merged seam is not valid; returns the command's exit code (0 when it is).
int report_invalid_seam(const mesh_merge::SeamQuality& q);

// `lapis merge --mode optimal` (cmd_merge_optimal.cpp).
int run_optimal_merge(const Args& args);

}  // namespace lapis::cli
