#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_set>

#include "conforming_zip.h"

#include "lapis/geometry/mesh_edit.h"
#include "lapis/mesh_merge/zip.h"

namespace lapis::mesh_merge {

namespace {

Eigen::Vector3d face_normal(const TriMesh& m, int f) {
  const Eigen::Vector3d a = m.V.row(m.F(f, 0)).transpose(), b = m.V.row(m.F(f, 1)).transpose(),
                        c = m.V.row(m.F(f, 2)).transpose();
  return (b - a).cross(c - a).normalized();
}

// How faces f and g turn against each other and their neighbours across their other edges
// (in `conn`: rows rewritten by a flip keep their outer edges' incidences): the folded pairs
// among them, then the smallest cosine, compared in that order.
struct Turn {
  int folded = 0;
  double worst = 1;
  // The worst turn first: a flip that trades a sharp fold for a milder one lets the umbrella
  // steps after it finish the job (unfold_seam keeps the better of with and without flips).
  bool better_than(const Turn& o) const { return worst != o.worst ? worst > o.worst : folded < o.folded; }
};

Turn turn_of(const TriMesh& m, const Connectivity& conn, int f, int g, double cos_fold) {
  Turn t;
  auto add = [&](int a, int b) {
    const double c = face_normal(m, a).dot(face_normal(m, b));
    t.folded += !(c >= cos_fold);
    t.worst = std::min(t.worst, std::isfinite(c) ? c : -2.0);
  };
  add(f, g);
  for (int h : {f, g})
    for (int k = 0; k < 3; ++k) {
      const int e = conn.find_edge(m.F(h, k), m.F(h, (k + 1) % 3));
      if (e < 0) continue;
      for (int x : conn.edge_faces(e))
        if (x >= 0 && x != f && x != g) add(h, x);
    }
  return t;
}

// Whether a face across an outer edge of f or g was flipped in this pass: `conn` no longer
// knows its edges, so turn_of() would not see how it meets f and g.
bool neighbour_touched(const TriMesh& m, const Connectivity& conn, int f, int g, const std::vector<char>& touched) {
  for (int h : {f, g})
    for (int k = 0; k < 3; ++k) {
      const int e = conn.find_edge(m.F(h, k), m.F(h, (k + 1) % 3));
      if (e < 0) continue;
      for (int x : conn.edge_faces(e))
        if (x >= 0 && x != f && x != g && touched[static_cast<size_t>(x)]) return true;
    }
  return false;
}

// Two strip faces on one inner edge: f = (x, y, b) and g = (y, x, d); flipped, (x, d, b) and
// (d, y, b), so both keep their indices.
struct StripPair {
  int f, g, x, y, b, d;
  void flip(TriMesh& m) const { m.F.row(f) << x, d, b, m.F.row(g) << d, y, b; }
};

// Passes over the strip's inner edges, each on a fresh connectivity and flipping a face at
// most once, offering every pair whose other diagonal is not an edge yet to
// accept(conn, pair), which may flip it and says whether to keep that; otherwise the pair's
// rows are restored. Stops after a pass without flips or max_passes passes; returns the flips.
// skip_beside_flipped: pairs next to a face flipped in the same pass wait for the next one.
template <class Accept>
int flip_strip_pairs(TriMesh& mesh, const std::vector<int>& strip_faces, int max_passes, bool skip_beside_flipped,
                     const Accept& accept) {
  std::vector<char> in_strip(static_cast<size_t>(mesh.num_faces()), 0);
  for (int f : strip_faces) in_strip[static_cast<size_t>(f)] = 1;
  int flips = 0;
  for (int pass = 0; pass < max_passes; ++pass) {
    const Connectivity conn(mesh);
    int pass_flips = 0;
    std::vector<char> touched(static_cast<size_t>(mesh.num_faces()), 0);
    // Diagonals this pass made, which `conn` does not know: flipping onto one of them would make
    // two faces on the same three vertices.
    std::unordered_set<std::uint64_t> made;
    for (int f : strip_faces)
      for (int j = 0; j < 3 && !touched[static_cast<size_t>(f)]; ++j) {
        const auto [p, q] = conn.edge_faces(conn.face_edge(f, j));
        const int g = p == f ? q : p;
        if (g < 0 || !in_strip[static_cast<size_t>(g)] || touched[static_cast<size_t>(g)]) continue;
        StripPair pair{f, g, mesh.F(f, j), mesh.F(f, (j + 1) % 3), mesh.F(f, (j + 2) % 3), -1};
        for (int k = 0; k < 3; ++k)
          if (mesh.F(g, k) != pair.x && mesh.F(g, k) != pair.y) pair.d = mesh.F(g, k);
        if (pair.d < 0 || pair.d == pair.b || conn.find_edge(pair.b, pair.d) >= 0) continue;
        const std::uint64_t diagonal = detail::directed_edge(std::min(pair.b, pair.d), std::max(pair.b, pair.d));
        if (made.count(diagonal) || (skip_beside_flipped && neighbour_touched(mesh, conn, f, g, touched))) continue;
        const Eigen::RowVector3i old_f = mesh.F.row(f), old_g = mesh.F.row(g);
        if (!accept(conn, pair)) {
          mesh.F.row(f) = old_f, mesh.F.row(g) = old_g;
          continue;
        }
        touched[static_cast<size_t>(f)] = touched[static_cast<size_t>(g)] = 1;
        made.insert(diagonal);
        ++pass_flips;
      }
    flips += pass_flips;
    if (pass_flips == 0) break;
  }
  return flips;
}

// Flips a folded inner edge of the strip where the other diagonal turns the two faces and their
// neighbours by less than before. The strip's tiling was chosen on the loops before smoothing,
// and a zig-zag left across a fold often has the other diagonal flat. Returns the flips.
int flip_folded_diagonals(TriMesh& mesh, const std::vector<int>& strip_faces, double cos_fold) {
  return flip_strip_pairs(mesh, strip_faces, 8, false, [&](const Connectivity& conn, const StripPair& p) {
    if (face_normal(mesh, p.f).dot(face_normal(mesh, p.g)) >= cos_fold) return false;
    const Turn before = turn_of(mesh, conn, p.f, p.g, cos_fold);
    p.flip(mesh);
    return turn_of(mesh, conn, p.f, p.g, cos_fold).better_than(before);
  });
}

// Umbrella steps on the vertices of folded strip edges' faces that may move, at most
// max_rounds; returns the folded edges left.
int smooth_out_folds(TriMesh& mesh, const std::vector<int>& strip_faces, const std::vector<char>& can_move,
                     int max_rounds, double lambda, double cos_fold) {
  const Connectivity conn(mesh);
  std::vector<int> edges;
  for (int f : strip_faces)
    for (int k = 0; k < 3; ++k)
      if (conn.edge_face_count(conn.face_edge(f, k)) == 2) edges.push_back(conn.face_edge(f, k));
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  auto folded_edges = [&] {
    std::vector<int> out;
    for (int e : edges) {
      const auto [f, g] = conn.edge_faces(e);
      if (!(face_normal(mesh, f).dot(face_normal(mesh, g)) >= cos_fold)) out.push_back(e);
    }
    return out;
  };
  std::vector<int> folded = folded_edges();
  for (int round = 0; round < max_rounds && !folded.empty(); ++round) {
    std::vector<int> verts;
    for (int e : folded)
      for (int f : conn.edge_faces(e))
        for (int k = 0; k < 3; ++k)
          if (can_move[mesh.F(f, k)]) verts.push_back(mesh.F(f, k));
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    if (verts.empty()) break;
    Vertices next(static_cast<Eigen::Index>(verts.size()), 3);
    for (size_t k = 0; k < verts.size(); ++k) {
      Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
      const auto nb = conn.vertex_neighbors(verts[k]);
      for (int u : nb) mean += mesh.V.row(u);
      next.row(static_cast<Eigen::Index>(k)) =
          mesh.V.row(verts[k]) + lambda * (mean / double(nb.size()) - mesh.V.row(verts[k]));
    }
    for (size_t k = 0; k < verts.size(); ++k) mesh.V.row(verts[k]) = next.row(static_cast<Eigen::Index>(k));
    folded = folded_edges();
  }
  return static_cast<int>(folded.size());
}

double smallest_angle(const TriMesh& m, int p, int q, int r) {
  const Eigen::Vector3d a = m.V.row(p).transpose(), b = m.V.row(q).transpose(), c = m.V.row(r).transpose();
  const auto angle = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return std::min({angle(b - a, c - a), angle(a - b, c - b), angle(a - c, b - c)});
}

// Flips an inner edge of the strip where the other diagonal raises the pair's smallest angle
// by more than rounding (a tie stays, so a turned copy of the input tiles alike). Folds are
// unfold_seam()'s: a pair beside one is left as it is, and no flip makes one.
int flip_thin_pairs(TriMesh& mesh, const std::vector<int>& strip_faces) {
  const double cos_fold = std::cos(geometry::kFoldedDihedralDeg * std::numbers::pi / 180);
  return flip_strip_pairs(mesh, strip_faces, 16, true, [&](const Connectivity& conn, const StripPair& p) {
    const double before = std::min(smallest_angle(mesh, p.x, p.y, p.b), smallest_angle(mesh, p.y, p.x, p.d));
    const double after = std::min(smallest_angle(mesh, p.x, p.d, p.b), smallest_angle(mesh, p.d, p.y, p.b));
    if (!(after > before * (1 + 1e-6)) || turn_of(mesh, conn, p.f, p.g, cos_fold).folded > 0) return false;
    p.flip(mesh);
    return turn_of(mesh, conn, p.f, p.g, cos_fold).folded == 0;
  });
}

// The strip faces and every face with a corner on them, as a mesh of their own: the flips
// only rewrite strip faces and look at their neighbours, and a connectivity of the whole merged
// mesh per pass cost 50 ms at 50K vertices.
struct StripNeighbourhood {
  TriMesh mesh;
  std::vector<int> vertex_of;  // local vertex -> merged vertex
  std::vector<int> strip;      // strip_faces[k] is local face strip[k]
};

StripNeighbourhood strip_neighbourhood(const TriMesh& mesh, const std::vector<int>& strip_faces) {
  std::vector<int> local(static_cast<size_t>(mesh.num_vertices()), -1);
  StripNeighbourhood n;
  for (int f : strip_faces)
    for (int k = 0; k < 3; ++k) local[static_cast<size_t>(mesh.F(f, k))] = 0;
  std::vector<int> faces(strip_faces);
  std::vector<char> is_strip(static_cast<size_t>(mesh.num_faces()), 0);
  for (int f : strip_faces) is_strip[static_cast<size_t>(f)] = 1;
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (!is_strip[static_cast<size_t>(f)] &&
        (local[static_cast<size_t>(mesh.F(f, 0))] == 0 || local[static_cast<size_t>(mesh.F(f, 1))] == 0 ||
         local[static_cast<size_t>(mesh.F(f, 2))] == 0))
      faces.push_back(f);
  n.mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  std::vector<int> index(static_cast<size_t>(mesh.num_vertices()), -1);
  for (size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int v = mesh.F(faces[i], k);
      if (index[static_cast<size_t>(v)] < 0) {
        index[static_cast<size_t>(v)] = static_cast<int>(n.vertex_of.size());
        n.vertex_of.push_back(v);
      }
      n.mesh.F(static_cast<Eigen::Index>(i), k) = index[static_cast<size_t>(v)];
    }
  n.mesh.V.resize(static_cast<Eigen::Index>(n.vertex_of.size()), 3);
  for (size_t v = 0; v < n.vertex_of.size(); ++v)
    n.mesh.V.row(static_cast<Eigen::Index>(v)) = mesh.V.row(n.vertex_of[v]);
  for (size_t k = 0; k < strip_faces.size(); ++k) n.strip.push_back(static_cast<int>(k));
  return n;
}

}  // namespace

int flip_thin_diagonals(TriMesh& mesh, const std::vector<int>& strip_faces) {
  StripNeighbourhood n = strip_neighbourhood(mesh, strip_faces);
  const int flips = flip_thin_pairs(n.mesh, n.strip);
  for (size_t k = 0; k < strip_faces.size(); ++k)
    for (int c = 0; c < 3; ++c)
      mesh.F(strip_faces[k], c) = n.vertex_of[static_cast<size_t>(n.mesh.F(static_cast<Eigen::Index>(k), c))];
  return flips;
}

int unfold_seam(TriMesh& mesh, const std::vector<int>& strip_faces, const std::vector<int>& movable, int max_rounds,
                double lambda) {
  const double cos_fold = std::cos(geometry::kFoldedDihedralDeg * std::numbers::pi / 180);
  std::vector<char> can_move(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : movable) can_move[v] = 1;
  // Flips first, then umbrella steps; the steps can turn a fold the flips could not undo into
  // one they can, so twice. Flips may leave more folds where nothing may move, so the umbrella
  // steps alone are tried too, and the result with fewer folds is kept.
  if (smooth_out_folds(mesh, strip_faces, can_move, 0, lambda, cos_fold) == 0) return 0;  // the usual case
  const TriMesh original = mesh;
  int folded = 0;
  for (int cycle = 0; cycle < 2; ++cycle) {
    flip_folded_diagonals(mesh, strip_faces, cos_fold);
    folded = smooth_out_folds(mesh, strip_faces, can_move, max_rounds, lambda, cos_fold);
    if (folded == 0) return 0;
  }
  TriMesh unflipped = original;
  const int without_flips = smooth_out_folds(unflipped, strip_faces, can_move, max_rounds, lambda, cos_fold);
  if (without_flips < folded) {
    mesh = std::move(unflipped);
    folded = without_flips;
  }
  return folded;
}

}  // namespace lapis::mesh_merge
