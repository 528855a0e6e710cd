#include "lapis/mesh_merge/cut.h"

#include <algorithm>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::mesh_merge {

namespace {

// The largest face component of mesh's `faces`, as a mesh with its map back to mesh.
geometry::TriMesh largest_part(const geometry::TriMesh& mesh, const std::vector<int>& faces,
                               std::vector<int>& to_mesh) {
  geometry::TriMesh part{mesh.V, geometry::Faces(static_cast<Eigen::Index>(faces.size()), 3)};
  for (size_t k = 0; k < faces.size(); ++k) part.F.row(static_cast<Eigen::Index>(k)) = mesh.F.row(faces[k]);
  const geometry::Components comp = geometry::connected_components(part);
  std::vector<int> size(static_cast<size_t>(comp.count), 0);
  for (int c : comp.face_component) ++size[c];
  const int best = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  std::vector<int> drop;
  for (int f = 0; f < part.num_faces(); ++f)
    if (comp.face_component[f] != best) drop.push_back(f);
  std::vector<int> map;
  geometry::TriMesh out = geometry::remove_faces(part, drop, &map);
  to_mesh.assign(static_cast<size_t>(out.num_vertices()), -1);
  for (int v = 0; v < static_cast<int>(map.size()); ++v)
    if (map[v] >= 0) to_mesh[map[v]] = v;
  return out;
}

// Closes pinches: where the inside faces around a vertex form more than one fan, both parts
// would be non-manifold there (a bow tie no merge accepts), so every face around it joins the
// inside. Repeats until no vertex pinches (each round only adds faces, so it ends).
void close_pinches(const geometry::TriMesh& mesh, std::vector<char>& inside) {
  const geometry::Connectivity conn(mesh);
  for (bool changed = true; changed;) {
    changed = false;
    for (int v = 0; v < mesh.num_vertices(); ++v) {
      int borders = 0;  // edges at v with inside on one side only
      for (int e : conn.vertex_edges(v)) {
        const auto f = conn.edge_faces(e);
        const bool a = f[0] >= 0 && inside[static_cast<size_t>(f[0])],
                   b = f[1] >= 0 && inside[static_cast<size_t>(f[1])];
        borders += a != b;
      }
      if (borders <= 2) continue;
      for (int f : conn.vertex_faces(v)) {
        if (inside[static_cast<size_t>(f)]) continue;
        inside[static_cast<size_t>(f)] = 1;
        changed = true;
      }
    }
  }
}

// Holes: unpainted islands inside the region (a brush leaves gaps) would each become a loop of
// the cut part. Everything outside the largest component of the unpainted faces joins the
// inside, so the part has one rim where the region was one patch.
bool fill_holes(const geometry::TriMesh& mesh, std::vector<char>& inside) {
  std::vector<int> out;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (!inside[static_cast<size_t>(f)]) out.push_back(f);
  if (out.empty()) return false;
  geometry::TriMesh part{mesh.V, geometry::Faces(static_cast<Eigen::Index>(out.size()), 3)};
  for (size_t k = 0; k < out.size(); ++k) part.F.row(static_cast<Eigen::Index>(k)) = mesh.F.row(out[k]);
  const geometry::Components comp = geometry::connected_components(part);
  std::vector<int> size(static_cast<size_t>(comp.count), 0);
  for (int c : comp.face_component) ++size[static_cast<size_t>(c)];
  const int best = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
  bool changed = false;
  for (size_t k = 0; k < out.size(); ++k)
    if (comp.face_component[k] != best) inside[static_cast<size_t>(out[k])] = 1, changed = true;
  return changed;
}

}  // namespace

PlaneCut cut_by_plane(const geometry::TriMesh& mesh, const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  constexpr const char* fn = "mesh_merge::cut_by_plane()";
  if (!(normal.norm() > 0)) throw InvalidArgument(std::string(fn) + ": zero plane normal");
  geometry::require_indices_in_range(mesh, fn);
  std::vector<int> up, down;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d c = (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))) / 3.0;
    ((c - point).dot(normal) > 0 ? up : down).push_back(f);
  }
  if (up.empty() || down.empty()) throw InvalidArgument(std::string(fn) + ": the plane leaves one side empty");
  PlaneCut cut;
  cut.above = largest_part(mesh, up, cut.above_to_mesh);
  cut.below = largest_part(mesh, down, cut.below_to_mesh);
  return cut;
}

RegionCut cut_by_region(const geometry::TriMesh& mesh, const std::vector<int>& region) {
  constexpr const char* fn = "mesh_merge::cut_by_region()";
  geometry::require_indices_in_range(mesh, fn);
  std::vector<char> selected(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : region) {
    if (v < 0 || v >= mesh.num_vertices())
      throw InvalidArgument(std::string(fn) + ": region vertex " + std::to_string(v) + " out of range");
    selected[static_cast<size_t>(v)] = 1;
  }
  std::vector<char> inside(static_cast<size_t>(mesh.num_faces()), 0);
  for (int f = 0; f < mesh.num_faces(); ++f)
    inside[static_cast<size_t>(f)] = selected[mesh.F(f, 0)] && selected[mesh.F(f, 1)] && selected[mesh.F(f, 2)];
  if (std::find(inside.begin(), inside.end(), 1) != inside.end()) {
    close_pinches(mesh, inside);
    while (fill_holes(mesh, inside)) close_pinches(mesh, inside);  // only grows: ends
  }
  std::vector<int> in, out;
  for (int f = 0; f < mesh.num_faces(); ++f) (inside[static_cast<size_t>(f)] ? in : out).push_back(f);
  if (in.empty())
    throw InvalidArgument(std::string(fn) + ": no face has all three corners in the region, expected a painted area");
  if (out.empty()) throw InvalidArgument(std::string(fn) + ": the region covers the whole mesh, expected a part of it");
  RegionCut cut;
  cut.inside = largest_part(mesh, in, cut.inside_to_mesh);
  cut.outside = largest_part(mesh, out, cut.outside_to_mesh);
  return cut;
}

}  // namespace lapis::mesh_merge
