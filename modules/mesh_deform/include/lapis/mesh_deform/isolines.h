// Isolines of a per-vertex scalar field at given isovalues (Au et al. 2007, §4.1, §4.3): the
// segments where each triangle crosses a level, with their lengths l_k (the weights of Eq. 8).
// Robust to the cases a handle field has everywhere: a level through a vertex (a segment from
// the vertex to the opposite edge, or none where the level only touches it), a level along an
// edge (a flat handle region's border: the edge is counted once, by one of its two faces), a
// flat region at the level (no segment inside it), and several loops per isovalue.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/tri_mesh.h"

namespace lapis::mesh_deform {

// One end of a segment: the point Σ_k b[k] · corner k of the face. `key` names the point on
// the mesh so that segments of one loop share it: a vertex v as (v, v), an edge (a, b), a < b,
// as a·#V + b.
struct IsolinePoint {
  std::array<double, 3> b{0, 0, 0};
  std::int64_t key = 0;
};

struct IsolineSegment {
  int face = -1;
  int level = -1;  // index into the isovalues
  IsolinePoint p, q;
  double length = 0;  // on the positions the segments were extracted from
};

// Segments of every isovalue, ordered by face then level. field  #V; V, F the mesh. The
// level s is compared exactly: values equal to s count as on the level.
std::vector<IsolineSegment> extract_isolines(const geometry::Vertices& V, const geometry::Faces& F,
                                             const Eigen::VectorXd& field, const std::vector<double>& isovalues);

// Position of an isoline point on positions V (the rest mesh or a deformed one).
Eigen::Vector3d isoline_point(const geometry::Vertices& V, const geometry::Faces& F, int face, const IsolinePoint& p);

// Number of connected loops (or open curves) the segments of one level form, joined at shared keys.
int count_isoline_loops(const std::vector<IsolineSegment>& segments, int level);

}  // namespace lapis::mesh_deform
