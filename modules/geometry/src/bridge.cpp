// bridge_polylines(): the triangle strip between two polylines, tiled by dynamic programming
// over the (i, j) grid of Fuchs, Kedem & Uselton (1977): every tiling is a monotone path
// from (0, 0) to (n−1, m−1), one triangle per step.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <unordered_map>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/geometry/mesh_edit.h"

namespace lapis::geometry {
namespace {

constexpr const char* kFn = "geometry::bridge_polylines()";

// x shorter than y by more than rounding. Lengths equal up to rounding (both diagonals of a
// rectangle) are a tie, which the caller breaks by position along the polylines: a rule that a
// similarity of the mesh cannot change, where `<` on rounded values flips with the last bit.
bool shorter(double x, double y) { return x < y * (1 - 1e-9); }

bool has_directed_edge(const Faces& F, int a, int b) {
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (F(f, k) == a && F(f, (k + 1) % 3) == b) return true;
  return false;
}

std::uint64_t edge_key(int u, int v) {
  return (std::uint64_t(std::uint32_t(std::min(u, v))) << 32) | std::uint32_t(std::max(u, v));
}

// Zero for a triangle flat to rounding: its height under 1e-12 of its longest edge. Three
// points of one straight cut lie exactly on a line in the frame they were cut in and 1e-16
// off it in any other, where their "normal" points anywhere: without the tolerance, a
// similarity of the mesh changed the fold and degeneracy counts and so the tiling.
Eigen::Vector3d unit_normal(const TriMesh& m, int p, int q, int r) {
  const Eigen::Vector3d x = m.V.row(p).transpose(), y = m.V.row(q).transpose(), z = m.V.row(r).transpose();
  const Eigen::Vector3d n = (y - x).cross(z - x);
  const double len = n.norm();
  const double longest = std::max({(y - x).squaredNorm(), (z - x).squaredNorm(), (z - y).squaredNorm()});
  return len > 1e-12 * longest ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

// For each edge (u[k], u[k+1]), the unit normal of the mesh face on it (zero where none).
std::vector<Eigen::Vector3d> faces_beside(const TriMesh& mesh, const std::vector<int>& u) {
  std::unordered_map<std::uint64_t, int> edge_index;
  for (size_t k = 0; k + 1 < u.size(); ++k) edge_index.emplace(edge_key(u[k], u[k + 1]), static_cast<int>(k));
  std::vector<Eigen::Vector3d> normal(u.size(), Eigen::Vector3d::Zero());
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto it = edge_index.find(edge_key(mesh.F(f, k), mesh.F(f, (k + 1) % 3)));
      if (it != edge_index.end()) normal[it->second] = unit_normal(mesh, mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2));
    }
  return normal;
}

// Two faces fold when their normals are more than kFoldedDihedralDeg apart (zero normals:
// no face, or a degenerate one, which is counted apart).
bool fold(const Eigen::Vector3d& x, const Eigen::Vector3d& y) {
  static const double cos_fold = std::cos(kFoldedDihedralDeg * std::numbers::pi / 180);
  return !x.isZero() && !y.isZero() && x.dot(y) < cos_fold;
}

// Cost of a partial tiling, compared lexicographically: folded edges and degenerate
// triangles, then the total length of the diagonals (the minimal-length criterion of Fuchs
// et al.).
struct Cost {
  int folded = 0;
  double length = 0;
  bool operator<(const Cost& o) const { return folded != o.folded ? folded < o.folded : shorter(length, o.length); }
};
constexpr Cost kUnreached{1 << 30, 0};

class StripTiling {
 public:
  StripTiling(const TriMesh& mesh, std::vector<int> a, std::vector<int> b, bool flip)
      : mesh_(mesh),
        a_(std::move(a)),
        b_(std::move(b)),
        flip_(flip),
        beside_a_(faces_beside(mesh, a_)),
        beside_b_(faces_beside(mesh, b_)) {}

  // The triangles of the best tiling, in strip order. The shortest tiling comes first; the
  // tiling with the fewest folds is then sought among those whose path stays within
  // kCorridor steps of it. Unbounded, avoiding one fold could be worth any length: on loops
  // of uneven shape it bought fans of triangles reaching across the whole loop.
  Faces solve() const {
    const std::vector<std::uint8_t> anywhere(a_.size() * b_.size(), 1);
    const std::vector<std::uint8_t> steps = cheapest_path(corridor(cheapest_path(anywhere, false)), true);
    Faces strip(static_cast<Eigen::Index>(steps.size()), 3);
    size_t i = 0, j = 0;
    for (size_t t = 0; t < steps.size(); ++t) {
      strip.row(static_cast<Eigen::Index>(t)) = triangle(i, j, steps[t]);
      steps[t] == 0 ? ++i : ++j;
    }
    return strip;
  }

 private:
  static constexpr size_t kCorridor = 10;

  // The cells (i, j) within kCorridor steps along a and along b of a cell of the path.
  std::vector<std::uint8_t> corridor(const std::vector<std::uint8_t>& steps) const {
    const size_t n = a_.size(), m = b_.size();
    std::vector<std::uint8_t> inside(n * m, 0);
    size_t i = 0, j = 0;
    for (size_t t = 0; t <= steps.size(); ++t) {
      for (size_t x = i - std::min(i, kCorridor); x <= std::min(n - 1, i + kCorridor); ++x)
        for (size_t y = j - std::min(j, kCorridor); y <= std::min(m - 1, j + kCorridor); ++y) inside[x * m + y] = 1;
      if (t < steps.size()) steps[t] == 0 ? ++i : ++j;
    }
    return inside;
  }

  // The steps (0 = along a, 1 = along b) of the cheapest monotone path from (0, 0) to
  // (n−1, m−1) through the cells marked `allowed`: by length alone, or by folds first.
  std::vector<std::uint8_t> cheapest_path(const std::vector<std::uint8_t>& allowed, bool count_folds) const {
    const size_t n = a_.size(), m = b_.size();
    // came[(i·m + j)·2 + s]: the step before step s into (i, j).
    std::vector<std::uint8_t> came(n * m * 2, 0);
    std::vector<Cost> prev(m * 2, kUnreached), cur(m * 2, kUnreached);
    for (size_t i = 0; i < n; ++i) {
      std::fill(cur.begin(), cur.end(), kUnreached);
      for (size_t j = 0; j < m; ++j) {
        if (!allowed[i * m + j]) continue;
        if (i > 0) relax(prev, i - 1, j, 0, count_folds, cur[j * 2 + 0], came[(i * m + j) * 2 + 0]);
        if (j > 0) relax(cur, i, j - 1, 1, count_folds, cur[j * 2 + 1], came[(i * m + j) * 2 + 1]);
      }
      std::swap(prev, cur);
    }
    // prev now holds row n−1; walk back from the cheaper last step (along a on a tie).
    int s = prev[(m - 1) * 2 + 1] < prev[(m - 1) * 2 + 0] ? 1 : 0;
    std::vector<std::uint8_t> steps(n + m - 2);
    for (size_t i = n - 1, j = m - 1, t = n + m - 2; t-- > 0;) {
      const int before = came[(i * m + j) * 2 + s];
      steps[t] = static_cast<std::uint8_t>(s);
      s == 0 ? --i : --j;
      s = before;
    }
    return steps;
  }

  // Vertices of the triangle stepping from (i, j) along a (s = 0) or along b (s = 1), wound as
  // it is added to the mesh.
  Eigen::RowVector3i triangle(size_t i, size_t j, int s) const {
    Eigen::RowVector3i t =
        s == 0 ? Eigen::RowVector3i(a_[i], a_[i + 1], b_[j]) : Eigen::RowVector3i(a_[i], b_[j + 1], b_[j]);
    if (flip_) std::swap(t(1), t(2));
    return t;
  }
  Eigen::Vector3d normal(const Eigen::RowVector3i& t) const { return unit_normal(mesh_, t(0), t(1), t(2)); }

  // Offers the path into (i, j) by step `last` (unless it is the start) continued by step s to
  // the state `into`; keeps it when cheaper (the earlier `last` wins a tie).
  void relax(const std::vector<Cost>& row, size_t i, size_t j, int s, bool count_folds, Cost& into,
             std::uint8_t& came) const {
    const Eigen::Vector3d n = count_folds ? normal(triangle(i, j, s)) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d& beside = s == 0 ? beside_a_[i] : beside_b_[j];
    const double diagonal = s == 0 ? (mesh_.V.row(a_[i + 1]) - mesh_.V.row(b_[j])).norm()
                                   : (mesh_.V.row(a_[i]) - mesh_.V.row(b_[j + 1])).norm();
    for (int last = 0; last < 2; ++last) {
      Cost c;
      if (i == 0 && j == 0) {
        if (last == 1) continue;  // the start has no step before it
      } else {
        c = row[j * 2 + last];
        if (c.folded == kUnreached.folded) continue;
        if (count_folds) c.folded += fold(n, normal(triangle(last == 0 ? i - 1 : i, last == 0 ? j : j - 1, last)));
      }
      if (count_folds) c.folded += fold(n, beside) + n.isZero();
      c.length += diagonal;
      if (c < into) into = c, came = static_cast<std::uint8_t>(last);
    }
  }

  const TriMesh& mesh_;
  std::vector<int> a_, b_;
  bool flip_;
  std::vector<Eigen::Vector3d> beside_a_, beside_b_;
};

}  // namespace

int bridge_polylines(TriMesh& mesh, const std::vector<int>& a_in, const std::vector<int>& b_in, bool closed) {
  if (a_in.size() < 2 || b_in.size() < 2)
    throw InvalidArgument(std::string(kFn) + ": polylines have " + std::to_string(a_in.size()) + " and " +
                          std::to_string(b_in.size()) + " vertices, expected at least 2 each");
  for (const auto* line : {&a_in, &b_in})
    for (int v : *line)
      if (v < 0 || v >= mesh.num_vertices())
        throw InvalidArgument(std::string(kFn) + ": vertex " + std::to_string(v) + " out of range [0, " +
                              std::to_string(mesh.num_vertices()) + ")");
  std::vector<int> a = a_in, b = b_in;
  auto pos = [&](int v) { return mesh.V.row(v); };
  if (closed) {
    size_t best = 0;
    for (size_t j = 1; j < b.size(); ++j)
      if (shorter((pos(b[j]) - pos(a[0])).squaredNorm(), (pos(b[best]) - pos(a[0])).squaredNorm())) best = j;
    std::rotate(b.begin(), b.begin() + static_cast<std::ptrdiff_t>(best), b.end());
    a.push_back(a.front());
    b.push_back(b.front());
  }
  // Base orientation uses a's edges forward and b's edges backward; flip to match neighbours.
  const bool flip = has_directed_edge(mesh.F, a[0], a[1]) || has_directed_edge(mesh.F, b[1], b[0]);
  const Faces strip = StripTiling(mesh, std::move(a), std::move(b), flip).solve();
  const Eigen::Index old = mesh.F.rows();
  mesh.F.conservativeResize(old + strip.rows(), 3);
  mesh.F.bottomRows(strip.rows()) = strip;
  return static_cast<int>(strip.rows());
}

}  // namespace lapis::geometry
