// Meshes made from parameters, for tests, demos and benchmarks: grids, bars, cylinders,
// spheres, tori (genus 1 and 2), and Loop subdivision to scale any mesh up to millions of
// vertices. All are consistently oriented (normals outward / +z) and valid.
#pragma once

#include <cstdint>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

// nx by ny quads split into triangles, covering [0, width] x [0, height] at z = 0, normals +z.
// (nx + 1)(ny + 1) vertices, vertex (i, j) at index j * (nx + 1) + i.
TriMesh make_plane_grid(int nx, int ny, double width = 1.0, double height = 1.0);

// The same grid with interior vertices moved by up to jitter * cell size in x and y (uniform,
// reproducible from seed) and alternating diagonals: irregular triangles with a fixed
// boundary, the usual stress case for cotangent weights. jitter must be in [0, 0.25): then a
// vertex and the opposite edge of any triangle together move less than the triangle's
// height (1/sqrt(2) cell), so no triangle folds.
TriMesh make_irregular_grid(int nx, int ny, double jitter = 0.2, std::uint32_t seed = 1, double width = 1.0,
                            double height = 1.0);

// Closed surface of the box [0, sx] x [0, sy] x [0, sz] with nx, ny, nz segments per side:
// the bar used by deformation tests (thesis fig. 2.7).
TriMesh make_box_bar(int nx, int ny, int nz, double sx, double sy, double sz);

// Open cylinder around the z axis, z in [0, height]: n_around x n_height quads split into
// triangles, two boundary loops (z = 0 and z = height).
TriMesh make_cylinder(int n_around, int n_height, double radius = 1.0, double height = 1.0);

// Icosahedron refined subdivisions times by midpoint splitting and projected to the sphere:
// 10 * 4^s + 2 vertices.
TriMesh make_icosphere(int subdivisions, double radius = 1.0);

// Torus around the z axis: major radius R (centre of the tube), minor radius r.
TriMesh make_torus(int n_major, int n_minor, double R = 1.0, double r = 0.4);

// Genus 2: two tori side by side along x whose facing patches are cut out and joined by a
// short tube (bridge_polylines). Closed, manifold, consistently oriented.
TriMesh make_double_torus(int n_major = 32, int n_minor = 16, double R = 1.0, double r = 0.4);

// Loop subdivision (Loop 1987), levels times: each triangle becomes four; interior weights
// beta(n) = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n, boundary curves use the cubic B-spline
// rule (1/8, 3/4, 1/8) and boundary edge points are midpoints. Requires a mesh with indices
// in range; non-manifold edges are treated as creases.
// Throws ResourceLimit when the result would pass 2e9 faces.
TriMesh loop_subdivide(const TriMesh& mesh, int levels);

// Same 1-to-4 split with edge points at midpoints and old vertices kept (no smoothing):
// refines without changing the shape.
TriMesh midpoint_subdivide(const TriMesh& mesh, int levels);

}  // namespace lapis::geometry
