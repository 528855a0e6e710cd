// Per-face and per-vertex normals and areas: the shading, offset and local-frame inputs of
// every modeling module.
#pragma once

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// #F x 3 unit normals (b - a) x (c - a) / |...|; zero rows for degenerate faces.
Vertices face_normals(const TriMesh& mesh);

// #F areas.
Eigen::VectorXd face_areas(const TriMesh& mesh);

// #V x 3 unit normals: the sum of incident face normals weighted by face area (the
// unnormalized cross products), normalized; zero rows for isolated vertices.
Vertices vertex_normals(const TriMesh& mesh);

}  // namespace lapis::geometry
