// Tetrahedral meshes and point location in them: the coarse solid that encloses a surface in
// Zhao et al.'s subspace solver (§4.1), where every surface vertex is located once and keeps
// its barycentric coordinates (§4.2).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::geometry {

using Tets = Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor>;

struct TetMesh {
  Vertices V;  // #TV by 3
  Tets T;      // #T by 4 vertex indices, positively oriented: (b − a)·((c − a) × (d − a)) > 0
  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_tets() const { return static_cast<int>(T.rows()); }
};

// Signed volume of (a, b, c, d): positive for a positively oriented tetrahedron.
double tet_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& d);

// Barycentric coordinates of p in tet t (sum 1; all ≥ 0 inside).
Eigen::Vector4d tet_barycentric(const TetMesh& mesh, int t, const Eigen::Vector3d& p);

// A triangle shared by two tets: its corners ascending and the two tets.
struct SharedFace {
  std::array<int, 3> corners;
  std::array<int, 2> tets;
};

// Every face shared by two tets, ordered by corners (a conforming mesh's interior faces).
std::vector<SharedFace> shared_faces(const TetMesh& mesh);

// Throws InvalidArgument (starting with context) for an index out of range, a non-finite
// vertex or a tet whose volume is not positive, naming the tet.
void require_valid_tets(const TetMesh& mesh, const char* context);

// Where a point lies: its tet and barycentric coordinates there.
struct TetLocation {
  int tet = -1;
  Eigen::Vector4d barycentric = Eigen::Vector4d::Zero();
  bool inside = false;  // false: the point lies outside every tet and `tet` is the nearest one
};

// Point location by a uniform grid of tet bounding boxes (about one tet per cell). A point
// inside no tet goes to the nearest tet (Euclidean distance), with its unclamped barycentric
// coordinates there, so an affine function is still reproduced exactly.
class TetLocator {
 public:
  // Throws like require_valid_tets().
  explicit TetLocator(const TetMesh& mesh);
  // Throws InvalidArgument for a non-finite p.
  TetLocation locate(const Eigen::Vector3d& p) const;

 private:
  int nearest_tet(const Eigen::Vector3d& p) const;
  std::array<int, 3> cell_of(const Eigen::Vector3d& p) const;

  const TetMesh& mesh_;
  Eigen::Vector3d lo_;
  double cell_ = 1;
  std::array<int, 3> dims_{1, 1, 1};
  std::vector<int> offsets_, items_;  // tets per cell (CSR)
};

// A dependency-free enclosing solid: the cubes of a regular lattice that hold a point of the
// surface (its vertices, and samples on triangles longer than half a cube), plus the cubes
// they enclose (flood fill from outside), each split into six tetrahedra along its main
// diagonal (Kuhn), so neighbouring cubes' faces match. The cube size is chosen so that the
// solid has about target_vertices vertices. Not rotation-equivariant (the lattice follows the
// axes) and it may bridge nearby parts: the fallback and test case beside a mesher's output.
// Throws InvalidArgument for an empty or invalid mesh or target_vertices < 8.
TetMesh lattice_enclosure(const TriMesh& surface, int target_vertices);

}  // namespace lapis::geometry
