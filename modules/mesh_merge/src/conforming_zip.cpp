#include "conforming_zip.h"

#include <cstdint>
#include <unordered_map>

#include "lapis/geometry/mesh_edit.h"

namespace lapis::mesh_merge::detail {
namespace {

// Which target vertex (loop index) each source loop point becomes, -1 for inserted points.
std::vector<int> snap_points(const BoundaryCorrespondence& pair, int nt) {
  const size_t ns = pair.target_t.size();
  std::vector<int> snapped(ns, -1), owner(static_cast<size_t>(nt), -1);
  std::vector<double> owner_distance(static_cast<size_t>(nt), 2.0);
  for (size_t i = 0; i < ns; ++i) {
    const double t = pair.target_t[i];
    const int e = pair.target_edge[i];
    const int j = t <= 0.5 ? e : (e + 1) % nt;
    const double d = t <= 0.5 ? t : 1 - t;
    if (d > kSnapFraction || d >= owner_distance[static_cast<size_t>(j)]) continue;
    owner_distance[static_cast<size_t>(j)] = d;
    owner[static_cast<size_t>(j)] = static_cast<int>(i);
  }
  for (int j = 0; j < nt; ++j)
    if (owner[static_cast<size_t>(j)] >= 0) snapped[static_cast<size_t>(owner[static_cast<size_t>(j)])] = j;
  return snapped;
}

// The position of point i along the target loop, in target edges from target_loop[0].
double loop_parameter(const BoundaryCorrespondence& pair, const std::vector<int>& snapped, size_t i) {
  return snapped[i] >= 0 ? double(snapped[i]) : pair.target_edge[i] + pair.target_t[i];
}

}  // namespace

ConformingSeam zip_conforming(TriMesh& mesh, const std::vector<int>& T, const std::vector<int>& S,
                              const BoundaryCorrespondence& pair) {
  const int nt = static_cast<int>(T.size());
  const size_t ns = S.size();
  const std::vector<int> snapped = snap_points(pair, nt);
  std::vector<int> id(ns);  // the merged vertex each source point becomes
  std::vector<char> target_taken(static_cast<size_t>(nt), 0);
  for (size_t i = 0; i < ns; ++i) {
    id[i] = snapped[i] >= 0 ? T[static_cast<size_t>(snapped[i])] : S[i];
    if (snapped[i] >= 0) target_taken[static_cast<size_t>(snapped[i])] = 1;
  }
  // Insertions into target edge j (walked from T[j + 1] to T[j], the target face's direction:
  // points by decreasing t) and into source edge i (S[i] → S[i + 1]: target vertices by
  // increasing parameter).
  std::unordered_map<std::uint64_t, std::vector<int>> inserted;
  for (size_t i = ns; i-- > 0;)
    if (snapped[i] < 0) {
      const int j = pair.target_edge[i];
      inserted[directed_edge(T[static_cast<size_t>((j + 1) % nt)], T[static_cast<size_t>(j)])].push_back(S[i]);
    }
  for (size_t i = 0; i < ns; ++i) {
    const double from = loop_parameter(pair, snapped, i);
    double to = loop_parameter(pair, snapped, (i + 1) % ns);
    if (to <= from) to += nt;
    std::vector<int> run;
    for (int j = static_cast<int>(std::floor(from)) + 1; j < to; ++j)
      if (!target_taken[static_cast<size_t>(j % nt)]) run.push_back(T[static_cast<size_t>(j % nt)]);
    if (!run.empty()) inserted[directed_edge(S[i], S[(i + 1) % ns])] = std::move(run);
  }
  std::unordered_map<int, int> redirect;
  for (size_t i = 0; i < ns; ++i)
    if (snapped[i] >= 0) redirect[S[i]] = id[i];
  const auto merged = [&](int v) {
    const auto it = redirect.find(v);
    return it == redirect.end() ? v : it->second;
  };

  // The seam's faces: those on a loop edge, on either side (re-triangulated or not).
  std::unordered_map<std::uint64_t, char> loop_edge;
  for (int j = 0; j < nt; ++j)
    loop_edge[directed_edge(T[static_cast<size_t>((j + 1) % nt)], T[static_cast<size_t>(j)])] = 1;
  for (size_t i = 0; i < ns; ++i) loop_edge[directed_edge(S[i], S[(i + 1) % ns])] = 1;
  ConformingSeam seam;
  std::vector<int> touched;
  for (int f = 0; f < mesh.num_faces(); ++f) {
    bool on_loop = false, split = false;
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t e = directed_edge(mesh.F(f, k), mesh.F(f, (k + 1) % 3));
      on_loop = on_loop || loop_edge.count(e);
      split = split || inserted.count(e);
    }
    if (split)
      touched.push_back(f);
    else if (on_loop)
      seam.strip_faces.push_back(f);
  }
  for (int f : touched) {
    std::vector<int> polygon;
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      polygon.push_back(merged(a));
      if (const auto it = inserted.find(directed_edge(a, b)); it != inserted.end())
        polygon.insert(polygon.end(), it->second.begin(), it->second.end());
    }
    const geometry::Faces tris = geometry::triangulate_polygon(mesh.V, polygon);
    mesh.F.row(f) = tris.row(0);
    seam.strip_faces.push_back(f);
    const Eigen::Index old = mesh.F.rows();
    mesh.F.conservativeResize(old + tris.rows() - 1, 3);
    mesh.F.bottomRows(tris.rows() - 1) = tris.bottomRows(tris.rows() - 1);
    for (Eigen::Index t = old; t < mesh.F.rows(); ++t) seam.strip_faces.push_back(static_cast<int>(t));
  }
  seam.seam_vertices = T;
  for (size_t i = 0; i < ns; ++i) {
    if (snapped[i] < 0)
      seam.seam_vertices.push_back(S[i]);
    else
      seam.snapped.emplace_back(S[i], id[i]);
  }
  return seam;
}

}  // namespace lapis::mesh_merge::detail
