#include "lapis/geometry/procedural.h"

#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"

namespace lapis::geometry {
namespace {

void require_at_least(int value, int min, const char* fn, const char* what) {
  if (value < min)
    throw InvalidArgument(std::string(fn) + ": " + what + " = " + std::to_string(value) + ", expected at least " +
                          std::to_string(min));
}

// Triangulates an (nu x nv)-quad lattice whose vertex (i, j) is index(i, j); wraps are the
// caller's business (index may be periodic). alternate flips every other diagonal.
Faces lattice_faces(int nu, int nv, const auto& index, bool alternate = false) {
  Faces F(2 * nu * nv, 3);
  int t = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = index(i, j), b = index(i + 1, j), c = index(i + 1, j + 1), d = index(i, j + 1);
      if (alternate && (i + j) % 2) {
        F.row(t++) << a, b, d;
        F.row(t++) << b, c, d;
      } else {
        F.row(t++) << a, b, c;
        F.row(t++) << a, c, d;
      }
    }
  return F;
}

}  // namespace

TriMesh make_plane_grid(int nx, int ny, double width, double height) {
  require_at_least(nx, 1, "geometry::make_plane_grid()", "nx");
  require_at_least(ny, 1, "geometry::make_plane_grid()", "ny");
  TriMesh m;
  m.V.resize((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.V.row(j * (nx + 1) + i) << width * i / nx, height * j / ny, 0.0;
  m.F = lattice_faces(nx, ny, [&](int i, int j) { return j * (nx + 1) + i; });
  return m;
}

TriMesh make_irregular_grid(int nx, int ny, double jitter, std::uint32_t seed, double width, double height) {
  if (!(jitter >= 0 && jitter < 0.25))
    throw InvalidArgument("geometry::make_irregular_grid(): jitter = " + std::to_string(jitter) +
                          ", expected [0, 0.25) (larger can fold triangles)");
  TriMesh m = make_plane_grid(nx, ny, width, height);
  m.F = lattice_faces(
      nx, ny, [&](int i, int j) { return j * (nx + 1) + i; }, true);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  for (int j = 1; j < ny; ++j)
    for (int i = 1; i < nx; ++i) {
      m.V(j * (nx + 1) + i, 0) += u(rng) * width / nx;
      m.V(j * (nx + 1) + i, 1) += u(rng) * height / ny;
    }
  return m;
}

TriMesh make_box_bar(int nx, int ny, int nz, double sx, double sy, double sz) {
  constexpr const char* fn = "geometry::make_box_bar()";
  require_at_least(nx, 1, fn, "nx");
  require_at_least(ny, 1, fn, "ny");
  require_at_least(nz, 1, fn, "nz");
  // Six grids, each mapped onto one side with an outward normal, then welded at the edges.
  const int n[3] = {nx, ny, nz};
  const double s[3] = {sx, sy, sz};
  TriMesh box;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;  // (u, v, axis) is right-handed
      TriMesh g = make_plane_grid(n[u], n[v], s[u], s[v]);
      Vertices P(g.num_vertices(), 3);
      P.col(u) = g.V.col(0);
      P.col(v) = g.V.col(1);
      P.col(axis).setConstant(side * s[axis]);
      if (side == 0) g.F.col(1).swap(g.F.col(2));  // normal -axis
      const int offset = box.num_vertices();
      box.V.conservativeResize(offset + P.rows(), 3);
      box.V.bottomRows(P.rows()) = P;
      box.F.conservativeResize(box.F.rows() + g.F.rows(), 3);
      box.F.bottomRows(g.F.rows()) = g.F.array() + offset;
    }
  weld_vertices(box, 1e-9 * std::max({sx, sy, sz}));
  return box;
}

TriMesh make_cylinder(int n_around, int n_height, double radius, double height) {
  require_at_least(n_around, 3, "geometry::make_cylinder()", "n_around");
  require_at_least(n_height, 1, "geometry::make_cylinder()", "n_height");
  TriMesh m;
  m.V.resize(n_around * (n_height + 1), 3);
  for (int j = 0; j <= n_height; ++j)
    for (int i = 0; i < n_around; ++i) {
      const double t = 2 * std::numbers::pi * i / n_around;
      m.V.row(j * n_around + i) << radius * std::cos(t), radius * std::sin(t), height * j / n_height;
    }
  m.F = lattice_faces(n_around, n_height, [&](int i, int j) { return j * n_around + i % n_around; });
  return m;
}

TriMesh make_torus(int n_major, int n_minor, double R, double r) {
  require_at_least(n_major, 3, "geometry::make_torus()", "n_major");
  require_at_least(n_minor, 3, "geometry::make_torus()", "n_minor");
  TriMesh m;
  m.V.resize(n_major * n_minor, 3);
  for (int i = 0; i < n_major; ++i)
    for (int j = 0; j < n_minor; ++j) {
      const double u = 2 * std::numbers::pi * i / n_major, v = 2 * std::numbers::pi * j / n_minor;
      m.V.row(i * n_minor + j) << (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
          r * std::sin(v);
    }
  m.F = lattice_faces(n_major, n_minor, [&](int i, int j) { return (i % n_major) * n_minor + j % n_minor; });
  return m;
}

TriMesh make_icosphere(int subdivisions, double radius) {
  require_at_least(subdivisions, 0, "geometry::make_icosphere()", "subdivisions");
  const double p = (1 + std::sqrt(5.0)) / 2;
  TriMesh m;
  m.V.resize(12, 3);
  m.V << -1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, 0, 0, -1, p, 0, 1, p, 0, -1, -p, 0, 1, -p, p, 0, -1, p, 0, 1, -p, 0, -1,
      -p, 0, 1;
  m.F.resize(20, 3);
  m.F << 0, 11, 5, 0, 5, 1, 0, 1, 7, 0, 7, 10, 0, 10, 11, 1, 5, 9, 5, 11, 4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3, 9, 4, 3,
      4, 2, 3, 2, 6, 3, 6, 8, 3, 8, 9, 4, 9, 5, 2, 4, 11, 6, 2, 10, 8, 6, 7, 9, 8, 1;
  m = midpoint_subdivide(m, subdivisions);
  m.V.rowwise().normalize();
  m.V *= radius;
  return m;
}

TriMesh make_double_torus(int n_major, int n_minor, double R, double r) {
  require_at_least(n_major, 8, "geometry::make_double_torus()", "n_major");
  require_at_least(n_minor, 8, "geometry::make_double_torus()", "n_minor");
  // Torus vertex 0 is the outermost point (+x). Cutting the 8 triangles around it leaves a
  // hole bounded by one 8-vertex loop; the second torus is the first turned 180 degrees about
  // z, so the two holes face each other across a gap of r / 2.
  const double shift = R + r + 0.25 * r;
  std::vector<int> around_outer;  // the quads (i, j) with i in {n_major - 1, 0}, j in {n_minor - 1, 0}
  for (int j : {n_minor - 1, 0})
    for (int i : {n_major - 1, 0})
      around_outer.insert(around_outer.end(), {2 * (j * n_major + i), 2 * (j * n_major + i) + 1});
  TriMesh halves[2];
  std::vector<int> loops[2];
  for (int h = 0; h < 2; ++h) {
    halves[h] = remove_faces(make_torus(n_major, n_minor, R, r), around_outer);
    if (h == 1) halves[h].V.leftCols(2) *= -1;
    halves[h].V.col(0).array() += h == 0 ? -shift : shift;
    loops[h] = Connectivity(halves[h]).boundary_loops().at(0);
  }
  TriMesh m;
  const int n0 = halves[0].num_vertices();
  m.V.resize(n0 + halves[1].num_vertices(), 3);
  m.V << halves[0].V, halves[1].V;
  m.F.resize(halves[0].num_faces() + halves[1].num_faces(), 3);
  m.F << halves[0].F, (halves[1].F.array() + n0).matrix();
  // Seen from +x the first hole's loop turns clockwise and the mirrored one counter-clockwise:
  // reverse the second so both run the same way, as bridge_polylines expects.
  std::vector<int> b(loops[1].rbegin(), loops[1].rend());
  for (int& v : b) v += n0;
  bridge_polylines(m, loops[0], b, true);
  return m;
}

}  // namespace lapis::geometry
