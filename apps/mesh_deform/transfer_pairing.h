// The deform app's side of deformation transfer (Au et al. 2007, §6): a target mesh drawn
// beside the source, and its handles made by clicking where each source handle is on it, one
// click per part of the handle (the fixed region under four feet takes four). A click seeds a
// region on the target that grows along its edges, nearest vertices first, until it covers
// the same fraction of the target's area as its part covers of the source's; the fixed region
// is paired the same way and the target's ROI is what it leaves.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/tri_mesh.h"
#include "lapis/mesh_deform/deformer.h"

namespace lapis::deform_app {

// Regions grown from `seeds` at once along the mesh's edges (Dijkstra on edge lengths, each
// vertex to the seed that reaches it first), region k until its vertex areas reach
// `area_fractions[k]` of the mesh's area; region k holds at least its seed unless an earlier
// seed is the same vertex (then it is empty). Throws InvalidArgument for a seed out of range.
std::vector<std::vector<int>> grow_regions(const geometry::Vertices& V, const geometry::Connectivity& conn,
                                           const Eigen::VectorXd& vertex_areas, const std::vector<int>& seeds,
                                           const std::vector<double>& area_fractions);

// Where the target is drawn: scaled to the source's bounding-box diagonal and set beside it
// along +x, a fifth of a diagonal apart. The transfer itself runs in the target's own frame.
struct Placement {
  double scale = 1;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return scale * p + offset; }
  geometry::Vertices apply(const geometry::Vertices& V) const;
};
Placement place_beside(const geometry::TriMesh& source, const geometry::TriMesh& target);

// One source handle to pair: the fixed region (when the source has one) or a region handle.
struct PairSlot {
  std::string name;                // "fixed region", "handle 2"
  int label = -1;                  // the source's handle label (VertexLabels), -1 for the fixed region
  std::vector<double> part_areas;  // its parts' fractions of the source's area, largest first
  std::vector<int> seeds;          // the clicked target vertices, one per part, in click order
  std::vector<int> region;         // the target vertices it stands for
  std::string problem;             // why the slot cannot be used yet (empty: it can)

  int parts() const { return static_cast<int>(part_areas.size()); }
  bool placed() const { return static_cast<int>(seeds.size()) == parts(); }
};

// The connected parts of `vertices` on the mesh of `conn` as fractions of `vertex_areas`' sum,
// largest first; parts under 5% of the largest are left out (specks of paint).
std::vector<double> part_areas(const geometry::Connectivity& conn, const Eigen::VectorXd& vertex_areas,
                               const std::vector<int>& vertices);

class TransferPairing {
 public:
  explicit TransferPairing(geometry::TriMesh target);

  const geometry::TriMesh& target() const { return target_; }
  const geometry::Connectivity& connectivity() const { return conn_; }

  // Takes the source's selection (as painted): keeps the clicks of slots that are still there
  // with as many parts, regrows every region for the new areas. `handle_label` as in
  // LabelledSelection.
  void set_source(const geometry::TriMesh& source, const geometry::Connectivity& source_conn,
                  const mesh_deform::Selection& selection, const std::vector<int>& handle_label);
  // Adds target vertex `vertex` as the next part of slot `slot` (a slot already placed starts
  // over with it) and regrows the regions.
  void place(int slot, int vertex);
  void clear(int slot);

  const std::vector<PairSlot>& slots() const { return slots_; }
  // The first slot not placed, or -1.
  int next_unplaced() const;
  // Every slot placed without a problem.
  bool complete() const;
  // The target's Selection, paired index by index with the source's; only when complete().
  mesh_deform::Selection selection() const;
  // Bumped whenever the target's selection changes.
  std::uint64_t revision() const { return revision_; }

 private:
  void regrow();

  geometry::TriMesh target_;
  geometry::Connectivity conn_;
  Eigen::VectorXd areas_;
  std::vector<PairSlot> slots_;
  std::uint64_t revision_ = 0;
};

}  // namespace lapis::deform_app
