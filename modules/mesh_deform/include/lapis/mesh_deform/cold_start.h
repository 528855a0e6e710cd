// How the local–global methods (ARAP, the edge-based Laplacian, salient features) start a frame
// that has no previous result to start from: the first, or any without warm start. None of
// their papers fixes it (Sorkine & Alexa §4 suggest naive Laplacian editing).
#pragma once

namespace lapis::mesh_deform {

enum class ColdStart {
  // Every local transform starts as the blend of the region handles' rotations (and, where the
  // method models scale, their scales), weighted by a field that is 1 on a handle and 0 on the
  // fixed region: a motion shared by every handle is reproduced by the first solve, and a bend
  // starts near its result.
  HandleRotations,
  // Every local transform starts as the identity, so the first solve is the method's naive
  // Laplacian editing: CGAL's Surface_mesh_deformation, iteration for iteration, for ARAP.
  Identity,
};

}  // namespace lapis::mesh_deform
