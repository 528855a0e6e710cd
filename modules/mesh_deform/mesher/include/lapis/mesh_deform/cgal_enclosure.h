// The solid subspace of Zhao et al. §4.1 built with CGAL: Alpha_wrap_3 gives a surface that
// is guaranteed to enclose the input at a chosen offset (the containment §4.1's normal offsets
// only hope for), make_mesh_3 tetrahedralises it with ODT optimisation (Alliez et al. 2005, the
// paper's [44]). The only target of Lapis that compiles CGAL headers; the salient deformer
// takes its result through SalientDeformer::set_subspace().
#pragma once

#include "lapis/geometry/tet_mesh.h"

namespace lapis::mesh_deform {

struct EnclosureOptions {
  int target_vertices = 100;  // Table 1: 51–227; reached within a factor of about 1.5
  // Alpha_wrap_3's alpha and offset as fractions of the bounding box diagonal: alpha bounds the
  // size of cavities the wrap does not enter, the offset its distance from the input. A coarse
  // tet mesh's boundary facets cut the wrap's curves, so the offset must exceed that cut: at
  // ~100 vertices an offset of 0.02 leaves a third of the armadillo's vertices outside every
  // tet, 0.08 leaves 19 of 26K, 0.1 none of the camel's and 0.15 none of the armadillo's.
  double alpha_fraction = 0.05;
  double offset_fraction = 0.1;
  bool odt = true;   // ODT optimisation of the tetrahedra (§4.1's [44])
  int attempts = 4;  // cell-size corrections towards target_vertices
};

struct EnclosureReport {
  int wrap_vertices = 0, wrap_faces = 0;
  int attempts = 0;
  double wrap_ms = 0, mesh_ms = 0;
};

// A positively oriented tet mesh enclosing `surface`. Throws InvalidArgument for an invalid
// or empty surface or options out of range, and SolverFailure naming the stage ("alpha wrap",
// "tetrahedral meshing") when CGAL produces nothing usable.
geometry::TetMesh cgal_enclosure(const geometry::TriMesh& surface, const EnclosureOptions& options = {},
                                 EnclosureReport* report = nullptr);

}  // namespace lapis::mesh_deform
