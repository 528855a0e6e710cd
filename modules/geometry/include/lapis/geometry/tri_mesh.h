// The triangle mesh every Lapis module passes around: #V x 3 positions and #F x 3 vertex
// indices (libigl's V/F convention, row-major so a row is one contiguous vertex or face),
// plus on-demand validation that names the offending indices.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace lapis::geometry {

using Vertices = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct TriMesh {
  Vertices V;  // #V by 3 positions
  Faces F;     // #F by 3 vertex indices, counter-clockwise seen from outside
  int num_vertices() const { return static_cast<int>(V.rows()); }
  int num_faces() const { return static_cast<int>(F.rows()); }
};

// Whether the triangle (p0, p1, p2) is thin: |e1 x e2| <= tolerance * (longest edge)^2, i.e. its
// smallest height is at most `tolerance` times its longest edge (scale invariant). False when a
// coordinate is not finite: callers that may see NaN check finiteness themselves.
bool is_thin_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      double tolerance);

// What validate() checks. Tolerances are relative so that the check is scale invariant.
struct ValidationOptions {
  // A face is degenerate when |e1 x e2| <= degenerate_tolerance * (longest edge)^2, i.e. when
  // its smallest angle-ish measure is at rounding level; exact zero-area faces always are.
  double degenerate_tolerance = 1e-14;
  bool check_degenerate = true;
  bool check_duplicates = true;
  bool check_manifold = true;     // non-manifold edges and vertices
  bool check_orientation = true;  // a directed edge used by two faces (flipped neighbour)
};

// Problems found by validate(), each as the list of offending indices (ascending).
struct ValidationReport {
  std::vector<int> out_of_range_faces;                 // faces with an index outside [0, #V)
  std::vector<int> non_finite_vertices;                // NaN or Inf coordinates
  std::vector<int> degenerate_faces;                   // zero area or a repeated index
  std::vector<int> duplicate_faces;                    // same vertex set as an earlier face
  std::vector<std::array<int, 2>> non_manifold_edges;  // (a < b) shared by > 2 faces
  std::vector<int> non_manifold_vertices;              // faces around it form > 1 fan
  std::vector<std::array<int, 2>> misoriented_edges;   // directed edge (a, b) in 2 faces

  bool ok() const;
  // One line per problem kind, e.g. "2 degenerate faces: 5, 17"; lists are cut after
  // max_listed indices. Empty when ok().
  std::string summary(size_t max_listed = 10) const;
};

// Checks mesh without throwing. Manifold/orientation/duplicate checks skip faces whose
// indices are out of range (those are reported first).
ValidationReport validate(const TriMesh& mesh, const ValidationOptions& options = {});

// Throws lapis::InvalidArgument "<context>: invalid mesh: <summary>" when validate() finds
// a problem. context defaults to "geometry::require_valid()".
void require_valid(const TriMesh& mesh, const ValidationOptions& options = {},
                   std::string_view context = "geometry::require_valid()");

// Throws InvalidArgument (starting with context) unless every face index is in [0, #V);
// the cheap precondition of algorithms that do not need full validation.
void require_indices_in_range(const TriMesh& mesh, std::string_view context);

// Throws InvalidArgument (starting with context) naming the first vertex with a NaN or
// infinite coordinate: what the writers check before a file gets "nan" or "inf" in it.
void require_finite_vertices(const TriMesh& mesh, std::string_view context);

}  // namespace lapis::geometry
