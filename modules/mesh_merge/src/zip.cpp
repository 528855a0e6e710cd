#include "lapis/mesh_merge/zip.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <unordered_set>

#include "conforming_zip.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::mesh_merge {

namespace {

constexpr const char* kZip = "mesh_merge::zip_seams()";

// The target with the bands of the listed pairs removed (thesis §3.3.1) and, for each of those
// pairs, its inner loop or, where the band is not an annulus, why.
struct BandCut {
  TriMesh reduced;
  std::vector<int> map;                 // target vertex -> reduced index, -1 if removed
  std::vector<std::vector<int>> inner;  // per pair; empty for pairs zipped without a band
  std::vector<std::string> problem;     // per pair; empty when the band is an annulus
};

BandCut cut_bands(const TriMesh& target, const std::vector<BoundaryCorrespondence>& pairs,
                  const std::vector<char>& banded) {
  const int nt = target.num_vertices();
  // The band: every target face touching a merging loop vertex. Its other vertices form the
  // pair's inner loop once the band is gone.
  std::vector<int> loop_of(static_cast<size_t>(nt), -1);
  for (size_t p = 0; p < pairs.size(); ++p)
    if (banded[p])
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
  BandCut cut;
  cut.reduced = geometry::remove_faces(target, band, &cut.map);
  cut.inner.resize(pairs.size());
  cut.problem.resize(pairs.size());
  std::vector<int> inner_pair(static_cast<size_t>(cut.reduced.num_vertices()), -1);
  for (int v = 0; v < nt; ++v)
    if (cut.map[v] >= 0) inner_pair[cut.map[v]] = inner_of[v];
  std::vector<int> found(pairs.size(), 0);
  const Connectivity conn(cut.reduced);
  for (const auto& loop : conn.boundary_loops()) {
    const int p = inner_pair[loop[0]];
    if (p < 0) continue;  // another open boundary of the target, untouched
    for (int v : loop)
      if (inner_pair[v] != p) cut.problem[p] = "it runs into the band of another loop";
    std::vector<int> sorted = loop;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      cut.problem[p] = "removing it leaves an inner loop that passes through one vertex twice";
    ++found[p];
    cut.inner[p] = loop;
  }
  for (size_t p = 0; p < pairs.size(); ++p)
    if (banded[p] && cut.problem[p].empty() && found[p] != 1)
      cut.problem[p] = "removing it leaves " + std::to_string(found[p]) +
                       " inner loops: the target loop passes within one triangle of itself or of a thin part";
  return cut;
}

// Pairs whose source loop was placed on the target loop (the solve's boundary conditions) can
// be zipped without a band; the others (a transition region's rim) need one.
bool placed_on_target(const BoundaryCorrespondence& pair) {
  return !pair.target_loop.empty() && pair.target_t.size() == pair.source_loop.size() &&
         pair.target_edge.size() == pair.source_loop.size();
}

// Bands that are not annuli are not removed: those pairs are zipped conforming instead.
BandCut cut_annular_bands(const TriMesh& target, const std::vector<BoundaryCorrespondence>& pairs,
                          std::vector<char>& banded) {
  banded.assign(pairs.size(), 1);
  for (;;) {
    BandCut cut = cut_bands(target, pairs, banded);
    bool again = false;
    for (size_t p = 0; p < pairs.size(); ++p) {
      if (!banded[p] || cut.problem[p].empty()) continue;
      if (!placed_on_target(pairs[p]))
        throw InvalidArgument(std::string(kZip) + ": the band of target faces next to loop " + std::to_string(p) +
                              " is not an annulus (" + cut.problem[p] + ")");
      banded[p] = 0;
      again = true;
    }
    if (!again) return cut;
  }
}

// The merged loop of a pair zipped without a band, in merged indices; throws where another
// pair's band took a vertex or a face of it (two target loops within one triangle).
std::vector<int> kept_target_loop(const std::vector<int>& target_map, const TriMesh& merged,
                                  const BoundaryCorrespondence& pair, size_t p) {
  std::vector<int> loop;
  std::vector<char> on_loop(static_cast<size_t>(merged.num_vertices()), 0);
  for (int v : pair.target_loop) {
    loop.push_back(target_map[v]);
    if (loop.back() >= 0) on_loop[static_cast<size_t>(loop.back())] = 1;
  }
  std::unordered_set<std::uint64_t> edges;
  for (int f = 0; f < merged.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (on_loop[static_cast<size_t>(merged.F(f, k))])
        edges.insert(detail::directed_edge(merged.F(f, k), merged.F(f, (k + 1) % 3)));
  for (size_t j = 0; j < loop.size(); ++j) {
    const int a = loop[(j + 1) % loop.size()], b = loop[j];
    if (a < 0 || b < 0 || !edges.count(detail::directed_edge(a, b)))
      throw InvalidArgument(std::string(kZip) + ": target loop " + std::to_string(p) +
                            " passes within one triangle of another merging loop; the seams cannot be zipped apart");
  }
  return loop;
}

// Source vertices that became target vertices: redirected in every face, then dropped.
void drop_snapped(ZipResult& z, const std::vector<std::pair<int, int>>& snapped) {
  std::vector<int> to(static_cast<size_t>(z.mesh.num_vertices()));
  for (size_t v = 0; v < to.size(); ++v) to[v] = static_cast<int>(v);
  for (const auto& [from, into] : snapped) to[static_cast<size_t>(from)] = into;
  for (int f = 0; f < z.mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) z.mesh.F(f, k) = to[static_cast<size_t>(z.mesh.F(f, k))];
  const std::vector<int> compact = geometry::remove_unreferenced_vertices(z.mesh);
  const auto renumber = [&](int v) { return v < 0 ? -1 : compact[static_cast<size_t>(to[static_cast<size_t>(v)])]; };
  for (int& v : z.target_map) v = renumber(v);
  for (int& v : z.source_map) v = renumber(v);
  for (int& v : z.seam_vertices) v = renumber(v);
}

}  // namespace

ZipResult zip_seams(const TriMesh& target, const TriMesh& source, const std::vector<BoundaryCorrespondence>& pairs) {
  std::vector<char> banded;
  BandCut cut = cut_annular_bands(target, pairs, banded);
  ZipResult z;
  z.target_map = std::move(cut.map);
  const TriMesh& reduced = cut.reduced;
  const int offset = reduced.num_vertices();
  z.mesh.V.resize(offset + source.num_vertices(), 3);
  z.mesh.V.topRows(offset) = reduced.V;
  z.mesh.V.bottomRows(source.num_vertices()) = source.V;
  z.mesh.F.resize(reduced.num_faces() + source.num_faces(), 3);
  z.mesh.F.topRows(reduced.num_faces()) = reduced.F;
  z.mesh.F.bottomRows(source.num_faces()) = source.F.array() + offset;
  z.source_map.resize(source.num_vertices());
  for (int v = 0; v < source.num_vertices(); ++v) z.source_map[v] = v + offset;

  std::vector<std::pair<int, int>> snapped;
  for (size_t p = 0; p < pairs.size(); ++p) {
    std::vector<int> a;
    for (int v : pairs[p].source_loop) a.push_back(v + offset);
    if (banded[p]) {
      std::vector<int> b(cut.inner[p].rbegin(), cut.inner[p].rend());  // against the target's orientation, like a
      const int first = z.mesh.num_faces();
      const int added = geometry::bridge_polylines(z.mesh, a, b, true);
      for (int f = first; f < first + added; ++f) z.strip_faces.push_back(f);
      z.seam_vertices.insert(z.seam_vertices.end(), a.begin(), a.end());
      z.seam_vertices.insert(z.seam_vertices.end(), b.begin(), b.end());
      continue;
    }
    const std::vector<int> t = kept_target_loop(z.target_map, z.mesh, pairs[p], p);
    detail::ConformingSeam seam = detail::zip_conforming(z.mesh, t, a, pairs[p]);
    z.strip_faces.insert(z.strip_faces.end(), seam.strip_faces.begin(), seam.strip_faces.end());
    z.seam_vertices.insert(z.seam_vertices.end(), seam.seam_vertices.begin(), seam.seam_vertices.end());
    snapped.insert(snapped.end(), seam.snapped.begin(), seam.snapped.end());
  }
  if (!snapped.empty()) drop_snapped(z, snapped);
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
