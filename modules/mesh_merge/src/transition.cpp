#include "lapis/mesh_merge/transition.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cut_open.h"
#include "lapis/core/format.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/mesh_edit.h"
#include "lapis/solver/least_squares.h"
#include "uv_locator.h"

namespace lapis::mesh_merge {

namespace {

constexpr const char* kBand = "mesh_merge::transition_band()";
constexpr double kInf = std::numeric_limits<double>::infinity();

[[noreturn]] void fail(const char* which, const std::string& what) {
  throw InvalidArgument(std::string(kBand) + ": the " + which + " " + what);
}

}  // namespace

std::vector<double> arc_length_params(const Vertices& V, const std::vector<int>& loop) {
  const size_t n = loop.size();
  std::vector<double> u(n, 0.0);
  double total = 0;
  for (size_t i = 0; i < n; ++i) {
    u[i] = total;
    total += (V.row(loop[(i + 1) % n]) - V.row(loop[i])).norm();
  }
  if (total > 0)
    for (double& x : u) x /= total;
  return u;
}

namespace {

// §3.3.3: the band is every vertex whose shortest edge path to the merging boundary is
// shorter than the width; its faces are those touching such a vertex.
std::vector<int> band_faces(const TriMesh& mesh, const Connectivity& conn, const std::vector<int>& loop, double width,
                            const std::string& w, const char* which) {
  const int nv = mesh.num_vertices();
  geometry::DijkstraOptions d;
  d.max_distance = width;
  const geometry::ShortestPaths sp = geometry::dijkstra(conn, loop, geometry::edge_length_cost(mesh), d);
  std::vector<char> near(static_cast<size_t>(nv), 0);
  std::vector<int> faces;
  int beyond = 0;
  for (int v = 0; v < nv; ++v) {
    near[v] = sp.distance[v] < width;
    beyond += !near[v] && !conn.is_isolated_vertex(v);
  }
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (near[mesh.F(f, 0)] || near[mesh.F(f, 1)] || near[mesh.F(f, 2)]) faces.push_back(f);
  if (beyond == 0 || static_cast<int>(faces.size()) == mesh.num_faces())
    fail(which, "transition band " + w + " covers the whole mesh (no face is that far from the merging loop)");
  return faces;
}

// The band's inner rim: its boundary loop other than the merging loop, in the seam's
// direction. Throws unless the band is an annulus between the two.
std::vector<int> band_rim(const Connectivity& conn, const Connectivity& sc, const std::vector<int>& loop, bool reversed,
                          const std::string& w, const char* which) {
  const auto& borders = sc.boundary_loops();
  const std::string not_annulus = "transition band " + w +
                                  " is not an annulus between the merging loop and one inner rim (it reaches another "
                                  "boundary, wraps around a handle or pinches); choose a smaller width";
  int li = -1;
  for (size_t l = 0; l < borders.size(); ++l)
    if (std::find(borders[l].begin(), borders[l].end(), loop[0]) != borders[l].end()) li = static_cast<int>(l);
  if (borders.size() != 2 || li < 0 || borders[li].size() != loop.size() || geometry::euler_characteristic(sc) != 0)
    fail(which, not_annulus);
  std::vector<int> rim = borders[1 - li];
  std::vector<char> on_rim(static_cast<size_t>(sc.num_vertices()), 0);
  for (int v : rim) {
    // A rim on the mesh's border would leave the other side of the seam without a surface.
    if (on_rim[v] || conn.is_boundary_vertex(v)) fail(which, not_annulus);
    on_rim[v] = 1;
  }
  // Boundary loops keep the band on their left, so the rim runs against the loop's own
  // direction: flip it to the seam's direction.
  if (!reversed) std::reverse(rim.begin(), rim.end());
  return rim;
}

// The cut: a shortest path from the key vertex to the rim that leaves the loop at once.
std::vector<int> band_cut(const TriMesh& mesh, const Connectivity& sc, const std::vector<int>& loop,
                          const std::vector<int>& rim, const std::string& w, const char* which) {
  std::vector<char> on_loop(static_cast<size_t>(mesh.num_vertices()), 0);
  for (int v : loop) on_loop[v] = 1;
  auto cost = [&](int, int from, int to) {
    return from != loop[0] && on_loop[from] ? kInf : (mesh.V.row(from) - mesh.V.row(to)).norm();
  };
  const geometry::ShortestPaths cp = geometry::dijkstra(sc, {loop[0]}, cost);
  int end = -1;
  for (int v : rim)
    if (std::isfinite(cp.distance[v]) && (end < 0 || cp.distance[v] < cp.distance[end])) end = v;
  if (end < 0)
    fail(which, "transition band " + w + " cannot be cut from key vertex " + std::to_string(loop[0]) + " to its rim");
  return geometry::extract_path(cp, end);
}

// Parameter-domain vertices: one per band and rim vertex, a second (u = 1) per cut vertex,
// and the band's faces on them, cut open. Returns the u = 1 copies, one per cut vertex.
std::vector<int> cut_open_domain(TransitionBand& b, const Connectivity& sc, const geometry::Faces& F, bool reversed,
                                 const char* which) {
  const int nv = static_cast<int>(b.param_of.size());
  for (int v = 0; v < nv; ++v)
    if (!sc.is_isolated_vertex(v)) {
      b.param_of[v] = static_cast<int>(b.param_vertex.size());
      b.param_vertex.push_back(v);
    }
  std::vector<int> upper_copy(b.cut.size());
  for (size_t k = 0; k < b.cut.size(); ++k) {
    upper_copy[k] = static_cast<int>(b.param_vertex.size());
    b.param_vertex.push_back(b.cut[k]);
  }
  const detail::CutOpen open = detail::cut_open(sc, F, b.cut, reversed);
  if (open.failed_at >= 0)
    fail(which, "transition band cannot be cut open at vertex " + std::to_string(open.failed_at) +
                    " (its faces do not form one fan)");
  b.param_faces = open.faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const int v = open.faces(f, j);
      b.param_faces(f, j) = v < nv ? b.param_of[v] : upper_copy[v - nv];
    }
  return upper_copy;
}

// Boundary values on the square (loop at v = 0, rim at v = 1, the cut's two copies at u = 0
// and u = 1), then Tutte's embedding inside.
void embed_in_square(TransitionBand& b, const Vertices& V, const std::vector<double>& loop_u,
                     const std::vector<int>& upper_copy) {
  const std::vector<double> rim_u = arc_length_params(V, b.rim);
  const int np = static_cast<int>(b.param_vertex.size());
  b.uv = Eigen::MatrixX2d::Zero(np, 2);
  std::vector<char> fixed(static_cast<size_t>(np), 0);
  auto set = [&](int p, double u, double v) { b.uv(p, 0) = u, b.uv(p, 1) = v, fixed[p] = 1; };
  for (size_t i = 0; i < b.loop.size(); ++i) set(b.param_of[b.loop[i]], loop_u[i], 0.0);
  for (size_t i = 0; i < b.rim.size(); ++i) set(b.param_of[b.rim[i]], rim_u[i], 1.0);
  double cut_length = 0;
  std::vector<double> along(b.cut.size(), 0.0);
  for (size_t k = 1; k < b.cut.size(); ++k) along[k] = cut_length += (V.row(b.cut[k]) - V.row(b.cut[k - 1])).norm();
  for (size_t k = 0; k < b.cut.size(); ++k) {
    const double v = k + 1 == b.cut.size() ? 1.0 : along[k] / cut_length;
    set(b.param_of[b.cut[k]], 0.0, v);
    set(upper_copy[k], 1.0, v);
  }
  std::vector<int> inner, boundary;
  for (int p = 0; p < np; ++p) (fixed[p] ? boundary : inner).push_back(p);
  if (inner.empty()) return;
  TriMesh domain;
  domain.V = Vertices::Zero(np, 3);
  domain.F = b.param_faces;
  const Eigen::SparseMatrix<double> L = geometry::uniform_laplacian(domain);
  solver::SparseMatrix rows(static_cast<Eigen::Index>(inner.size()), np);
  std::vector<Eigen::Triplet<double, int>> t;
  for (size_t r = 0; r < inner.size(); ++r)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, inner[r]); it; ++it)
      t.emplace_back(static_cast<int>(r), static_cast<int>(it.row()), it.value());  // L is symmetric
  rows.setFromTriplets(t.begin(), t.end());
  solver::LeastSquares tutte(np);
  tutte.add_block(rows, 1.0, "Tutte embedding");
  tutte.set_fixed(boundary);
  tutte.precompute();
  solver::DenseMatrix values(static_cast<Eigen::Index>(boundary.size()), 2);
  for (size_t k = 0; k < boundary.size(); ++k) values.row(static_cast<Eigen::Index>(k)) = b.uv.row(boundary[k]);
  const solver::DenseMatrix x = tutte.solve({solver::DenseMatrix()}, values);
  for (int p : inner) b.uv.row(p) = x.row(p);
}

}  // namespace

bool band_is_annulus(const TriMesh& mesh, const Connectivity& conn, const std::vector<int>& loop, double width,
                     const char* which, std::string* why) {
  try {
    if (loop.size() < 3) fail(which, "merging loop needs at least 3 vertices");
    const std::string w = "of width " + format_number(width);
    const std::vector<int> faces = band_faces(mesh, conn, loop, width, w, which);
    const Connectivity sc(geometry::with_faces(mesh, faces));
    band_cut(mesh, sc, loop, band_rim(conn, sc, loop, false, w, which), w, which);
    return true;
  } catch (const InvalidArgument& e) {
    if (why) *why = e.what();
    return false;
  }
}

TransitionBand transition_band(const TriMesh& mesh, const Connectivity& conn, const std::vector<int>& loop,
                               const std::vector<double>& loop_u, double width, bool reversed, const char* which) {
  if (!(width > 0) || !std::isfinite(width))
    fail(which, "transition width must be finite and > 0, got " + format_number(width));
  if (loop.size() < 3 || loop_u.size() != loop.size())
    fail(which, "merging loop needs at least 3 vertices and one parameter per vertex");
  const int nv = mesh.num_vertices();
  const std::string w = "of width " + format_number(width);
  TransitionBand b;
  b.loop = loop;
  b.faces = band_faces(mesh, conn, loop, width, w, which);

  const TriMesh sub = geometry::with_faces(mesh, b.faces);
  const Connectivity sc(sub);
  std::vector<int> rim = band_rim(conn, sc, loop, reversed, w, which);
  std::vector<char> on_rim(static_cast<size_t>(nv), 0);
  for (int v : rim) on_rim[v] = 1;
  for (int v = 0; v < nv; ++v)
    if (!sc.is_isolated_vertex(v) && !on_rim[v]) b.vertices.push_back(v);

  b.cut = band_cut(mesh, sc, loop, rim, w, which);
  std::rotate(rim.begin(), std::find(rim.begin(), rim.end(), b.cut.back()), rim.end());
  b.rim = rim;
  b.param_of.assign(static_cast<size_t>(nv), -1);
  const std::vector<int> upper_copy = cut_open_domain(b, sc, sub.F, reversed, which);
  embed_in_square(b, mesh.V, loop_u, upper_copy);
  return b;
}

std::vector<BandPoint> overlap_points(const TransitionBand& from, const TransitionBand& to) {
  const detail::UvLocator locator(to.uv, to.param_faces);
  std::vector<BandPoint> out;
  out.reserve(from.vertices.size());
  for (int v : from.vertices) {
    const Eigen::Vector2d p = from.at(v);
    // The overlap: the loop of one band is the rim of the other.
    const detail::UvHit hit = locator.locate(Eigen::Vector2d(p.x(), 1 - p.y()));
    if (hit.face < 0)
      throw InvalidArgument(
          "mesh_merge::overlap_points(): the band's parameterization has no triangle of positive area");
    BandPoint bp;
    Eigen::Vector3d w = hit.weights.cwiseMax(0.0);
    w /= w.sum();
    for (int j = 0; j < 3; ++j) bp.vertices[j] = to.param_vertex[to.param_faces(hit.face, j)], bp.weights[j] = w(j);
    out.push_back(bp);
  }
  return out;
}

}  // namespace lapis::mesh_merge
