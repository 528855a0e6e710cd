#include "lapis/geometry/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>

#include <Eigen/Geometry>

#include "lapis/core/error.h"
#include "lapis/core/format.h"
#include "lapis/geometry/connectivity.h"
#include "parallel.h"

namespace lapis::geometry {
namespace {

bool face_in_range(const TriMesh& m, Eigen::Index f) {
  for (int k = 0; k < 3; ++k)
    if (m.F(f, k) < 0 || m.F(f, k) >= m.num_vertices()) return false;
  return true;
}

bool is_degenerate(const TriMesh& m, Eigen::Index f, double tolerance) {
  const int a = m.F(f, 0), b = m.F(f, 1), c = m.F(f, 2);
  return a == b || b == c || c == a || is_thin_triangle(m.V.row(a), m.V.row(b), m.V.row(c), tolerance);
}

std::uint64_t pair_key(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

void find_duplicates(const TriMesh& m, const std::vector<int>& faces, ValidationReport& r) {
  std::vector<std::array<int, 4>> keyed;  // sorted triple + face
  keyed.reserve(faces.size());
  for (int f : faces) {
    std::array<int, 4> k{m.F(f, 0), m.F(f, 1), m.F(f, 2), f};
    std::sort(k.begin(), k.begin() + 3);
    keyed.push_back(k);
  }
  std::sort(keyed.begin(), keyed.end());
  for (size_t i = 1; i < keyed.size(); ++i)
    if (std::equal(keyed[i].begin(), keyed[i].begin() + 3, keyed[i - 1].begin()))
      r.duplicate_faces.push_back(keyed[i][3]);
  std::sort(r.duplicate_faces.begin(), r.duplicate_faces.end());
}

// Edges used by more than two faces, and directed edges used twice (a flipped neighbour).
// One sort of undirected keys carrying the direction in the lowest bit serves both checks.
void find_edge_problems(const TriMesh& m, const std::vector<int>& faces, ValidationReport& r,
                        const ValidationOptions& o) {
  std::vector<std::uint64_t> keys(faces.size() * 3);
  for (size_t i = 0; i < faces.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(faces[i], k), b = m.F(faces[i], (k + 1) % 3);
      keys[3 * i + k] = pair_key(std::min(a, b), std::max(a, b)) << 1 | (a > b);  // indices < 2^31
    }
  std::sort(keys.begin(), keys.end());
  for (size_t i = 0; i < keys.size();) {
    size_t j = i;
    int forward = 0, backward = 0;
    for (; j < keys.size() && keys[j] >> 1 == keys[i] >> 1; ++j) (keys[j] & 1 ? backward : forward)++;
    const int lo = static_cast<int>(keys[i] >> 33), hi = static_cast<int>((keys[i] >> 1) & 0xffffffffu);
    if (o.check_manifold && j - i > 2) r.non_manifold_edges.push_back({lo, hi});
    if (o.check_orientation && forward > 1) r.misoriented_edges.push_back({lo, hi});
    if (o.check_orientation && backward > 1) r.misoriented_edges.push_back({hi, lo});
    i = j;
  }
}

// A vertex is manifold when its faces form one fan: connected through edges at the vertex.
// parent is scratch space, reused across calls.
bool single_fan(const Faces& F, int v, std::span<const int> faces, std::vector<int>& parent) {
  if (faces.size() <= 1) return true;
  parent.resize(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (size_t i = 0; i < faces.size(); ++i)
    for (size_t j = i + 1; j < faces.size(); ++j) {
      bool shared = false;  // a vertex other than v in both faces: they share an edge at v
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const int x = F(faces[i], a);
          shared |= x != v && x == F(faces[j], b);
        }
      if (shared) parent[find(static_cast<int>(i))] = find(static_cast<int>(j));
    }
  int roots = 0;
  for (size_t i = 0; i < faces.size(); ++i) roots += find(static_cast<int>(i)) == static_cast<int>(i);
  return roots == 1;
}

template <class T>
void list(std::ostringstream& out, const char* what, const std::vector<T>& items, size_t max) {
  if (items.empty()) return;
  if (out.tellp() > 0) out << "; ";
  out << items.size() << " " << what << ": ";
  for (size_t i = 0; i < items.size() && i < max; ++i) {
    if (i) out << ", ";
    if constexpr (std::is_same_v<T, int>)
      out << items[i];
    else
      out << "(" << items[i][0] << ", " << items[i][1] << ")";
  }
  if (items.size() > max) out << ", ...";
}

}  // namespace

bool is_thin_triangle(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                      double tolerance) {
  const Eigen::Vector3d e0 = p1 - p0, e1 = p2 - p1, e2 = p0 - p2;
  const double longest2 = std::max({e0.squaredNorm(), e1.squaredNorm(), e2.squaredNorm()});
  return e0.cross(-e2).norm() <= tolerance * longest2;
}

bool ValidationReport::ok() const {
  return out_of_range_faces.empty() && non_finite_vertices.empty() && degenerate_faces.empty() &&
         duplicate_faces.empty() && non_manifold_edges.empty() && non_manifold_vertices.empty() &&
         misoriented_edges.empty();
}

std::string ValidationReport::summary(size_t max_listed) const {
  std::ostringstream out;
  list(out, "faces with out-of-range indices", out_of_range_faces, max_listed);
  list(out, "vertices with non-finite coordinates", non_finite_vertices, max_listed);
  list(out, "degenerate faces", degenerate_faces, max_listed);
  list(out, "duplicate faces", duplicate_faces, max_listed);
  list(out, "non-manifold edges", non_manifold_edges, max_listed);
  list(out, "non-manifold vertices", non_manifold_vertices, max_listed);
  list(out, "misoriented edges", misoriented_edges, max_listed);
  return out.str();
}

ValidationReport validate(const TriMesh& m, const ValidationOptions& o) {
  ValidationReport r;
  for (int v = 0; v < m.num_vertices(); ++v)
    if (!m.V.row(v).allFinite()) r.non_finite_vertices.push_back(v);
  std::vector<int> good;  // faces in range, the only ones the topological checks can look at
  good.reserve(m.F.rows());
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    if (!face_in_range(m, f)) {
      r.out_of_range_faces.push_back(static_cast<int>(f));
      continue;
    }
    good.push_back(static_cast<int>(f));
    if (o.check_degenerate && is_degenerate(m, f, o.degenerate_tolerance))
      r.degenerate_faces.push_back(static_cast<int>(f));
  }
  if (o.check_duplicates) find_duplicates(m, good, r);
  if (o.check_manifold || o.check_orientation) find_edge_problems(m, good, r, o);
  if (o.check_manifold) {
    Faces in_range(good.size(), 3);
    for (size_t i = 0; i < good.size(); ++i) in_range.row(i) = m.F.row(good[i]);
    const AdjacencyLists vf = vertex_face_lists(in_range, m.num_vertices());
    std::vector<char> bad(m.num_vertices(), 0);
#pragma omp parallel if (m.num_vertices() >= detail::kParallelMin)
    {
      std::vector<int> scratch;
#pragma omp for schedule(dynamic, 4096)
      for (int v = 0; v < m.num_vertices(); ++v) bad[v] = !single_fan(in_range, v, vf[v], scratch);
    }
    for (int v = 0; v < m.num_vertices(); ++v)
      if (bad[v]) r.non_manifold_vertices.push_back(v);
  }
  return r;
}

void require_valid(const TriMesh& mesh, const ValidationOptions& options, std::string_view context) {
  const ValidationReport r = validate(mesh, options);
  if (!r.ok()) throw InvalidArgument(std::string(context) + ": invalid mesh: " + r.summary());
}

void require_indices_in_range(const TriMesh& mesh, std::string_view context) {
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (!face_in_range(mesh, f)) {
      std::ostringstream out;
      out << context << ": face " << f << " = (" << mesh.F(f, 0) << ", " << mesh.F(f, 1) << ", " << mesh.F(f, 2)
          << ") has an index outside [0, " << mesh.num_vertices() << ")";
      throw InvalidArgument(out.str());
    }
}

void require_finite_vertices(const TriMesh& mesh, std::string_view context) {
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v)
    if (!mesh.V.row(v).allFinite()) {
      std::ostringstream out;
      out << context << ": vertex " << v << " = (" << format_number(mesh.V(v, 0)) << ", " << format_number(mesh.V(v, 1))
          << ", " << format_number(mesh.V(v, 2)) << ") is not finite";
      throw InvalidArgument(out.str());
    }
}

}  // namespace lapis::geometry
