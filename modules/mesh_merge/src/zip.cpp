#include "lapis/mesh_merge/zip.h"

#include <algorithm>
#include <string>

#include "lapis/geometry/mesh_edit.h"

namespace lapis::mesh_merge {

namespace {
constexpr const char* kZip = "mesh_merge::zip_seams()";
}

ZipResult zip_seams(const TriMesh& target, const TriMesh& source, const std::vector<BoundaryCorrespondence>& pairs) {
  const int nt = target.num_vertices();
  // The band: every target face touching a merging loop vertex. Its other vertices form the
  // pair's inner loop once the band is gone.
  std::vector<int> loop_of(static_cast<size_t>(nt), -1);
  for (size_t p = 0; p < pairs.size(); ++p)
    for (int v : pairs[p].target_loop) loop_of[v] = static_cast<int>(p);
  std::vector<int> band, inner_of(static_cast<size_t>(nt), -1);
  for (int f = 0; f < target.num_faces(); ++f) {
    int p = -1;
    for (int k = 0; k < 3; ++k) p = std::max(p, loop_of[target.F(f, k)]);
    if (p < 0) continue;
    band.push_back(f);
    for (int k = 0; k < 3; ++k)
      if (loop_of[target.F(f, k)] < 0) inner_of[target.F(f, k)] = p;
  }
  ZipResult z;
  TriMesh reduced = geometry::remove_faces(target, band, &z.target_map);
  std::vector<int> inner_pair(static_cast<size_t>(reduced.num_vertices()), -1);
  for (int v = 0; v < nt; ++v)
    if (z.target_map[v] >= 0) inner_pair[z.target_map[v]] = inner_of[v];
  const Connectivity conn(reduced);
  std::vector<std::vector<int>> inner(pairs.size());
  std::vector<int> found(pairs.size(), 0);
  for (const auto& loop : conn.boundary_loops()) {
    const int p = inner_pair[loop[0]];
    if (p < 0) continue;  // another open boundary of the target, untouched
    for (int v : loop)
      if (inner_pair[v] != p)
        throw InvalidArgument(std::string(kZip) + ": the band removed next to target loop " + std::to_string(p) +
                              " leaves a boundary running into another loop's band (target too thin there)");
    ++found[p];
    inner[p] = loop;
  }
  for (size_t p = 0; p < pairs.size(); ++p)
    if (found[p] != 1)
      throw InvalidArgument(std::string(kZip) + ": removing the band next to target loop " + std::to_string(p) +
                            " leaves " + std::to_string(found[p]) +
                            " inner loops, expected one (target too coarse next to its boundary)");

  const int offset = reduced.num_vertices();
  z.mesh.V.resize(offset + source.num_vertices(), 3);
  z.mesh.V.topRows(offset) = reduced.V;
  z.mesh.V.bottomRows(source.num_vertices()) = source.V;
  z.mesh.F.resize(reduced.num_faces() + source.num_faces(), 3);
  z.mesh.F.topRows(reduced.num_faces()) = reduced.F;
  z.mesh.F.bottomRows(source.num_faces()) = source.F.array() + offset;
  z.source_map.resize(source.num_vertices());
  for (int v = 0; v < source.num_vertices(); ++v) z.source_map[v] = v + offset;

  for (size_t p = 0; p < pairs.size(); ++p) {
    std::vector<int> a, b(inner[p].rbegin(), inner[p].rend());  // b against the target's orientation, like a
    for (int v : pairs[p].source_loop) a.push_back(v + offset);
    const int first = z.mesh.num_faces();
    const int added = geometry::bridge_polylines(z.mesh, a, b, true);
    for (int f = first; f < first + added; ++f) z.strip_faces.push_back(f);
    z.seam_vertices.insert(z.seam_vertices.end(), a.begin(), a.end());
    z.seam_vertices.insert(z.seam_vertices.end(), b.begin(), b.end());
  }
  std::sort(z.seam_vertices.begin(), z.seam_vertices.end());
  z.seam_vertices.erase(std::unique(z.seam_vertices.begin(), z.seam_vertices.end()), z.seam_vertices.end());
  return z;
}

std::vector<int> seam_band(const TriMesh& mesh, const std::vector<int>& seam_vertices, int rings) {
  std::vector<int> band = geometry::k_ring(Connectivity(mesh), seam_vertices, rings);
  std::sort(band.begin(), band.end());
  return band;
}

void umbrella_smooth(TriMesh& mesh, const std::vector<int>& vertices, int iterations, double lambda) {
  constexpr const char* fn = "mesh_merge::umbrella_smooth()";
  if (!(lambda > 0 && lambda <= 1)) throw InvalidArgument(std::string(fn) + ": lambda must be in (0, 1]");
  if (iterations < 0) throw InvalidArgument(std::string(fn) + ": iterations must be >= 0");
  for (int v : vertices)
    if (v < 0 || v >= mesh.num_vertices())
      throw InvalidArgument(std::string(fn) + ": vertex " + std::to_string(v) + " out of range");
  if (iterations == 0 || vertices.empty()) return;
  const Connectivity conn(mesh);
  Vertices next(static_cast<Eigen::Index>(vertices.size()), 3);
  for (int it = 0; it < iterations; ++it) {
    // Jacobi: every vertex reads the previous iterate, so the order of `vertices` is irrelevant.
#pragma omp parallel for schedule(static)
    for (int k = 0; k < static_cast<int>(vertices.size()); ++k) {
      const int v = vertices[k];
      const auto nb = conn.vertex_neighbors(v);
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      for (int u : nb) mean += mesh.V.row(u);
      next.row(k) = nb.empty()
                        ? Eigen::RowVector3d(mesh.V.row(v))
                        : Eigen::RowVector3d(mesh.V.row(v) + lambda * (mean / double(nb.size()) - mesh.V.row(v)));
    }
    for (size_t k = 0; k < vertices.size(); ++k) mesh.V.row(vertices[k]) = next.row(static_cast<Eigen::Index>(k));
  }
}

}  // namespace lapis::mesh_merge
