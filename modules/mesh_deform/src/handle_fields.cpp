#include "lapis/mesh_deform/handle_fields.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "lapis/geometry/dijkstra.h"
#include "lapis/geometry/laplacian.h"
#include "lapis/geometry/normals.h"
#include "lapis/solver/cholesky.h"

namespace lapis::mesh_deform {
namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double bbox_diagonal(const Vertices& V) { return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm(); }

// The point handle's vertex, its 1-ring and every vertex within `radius` along edges, as long
// as it is free and not yet claimed.
std::vector<int> point_disc(const geometry::Connectivity& conn, const TriMesh& mesh, int v, double radius,
                            const Layout& layout, std::vector<char>& claimed) {
  std::vector<int> disc{v};
  claimed[v] = 1;
  geometry::DijkstraOptions o;
  o.max_distance = radius;
  const auto paths = geometry::dijkstra(conn, {v}, geometry::edge_length_cost(mesh), o);
  const auto ring = geometry::k_ring(conn, {v}, 1);
  auto take = [&](int u) {
    if (claimed[u] || layout.role[u] != VertexRole::Free) return;
    claimed[u] = 1;
    disc.push_back(u);
  };
  for (int u : ring) take(u);
  for (int u = 0; u < mesh.num_vertices(); ++u)
    if (paths.distance[u] <= radius) take(u);
  return disc;
}

}  // namespace

HandleSets handle_sets(const TriMesh& mesh, const Layout& layout, const Selection& selection,
                       const HandleFieldOptions& options) {
  HandleSets sets;
  std::vector<int> fixed;
  for (int v : layout.constrained)
    if (layout.role[v] == VertexRole::Fixed) fixed.push_back(v);
  sets.has_fixed_region = !fixed.empty();
  if (sets.has_fixed_region) sets.handle_vertices.push_back(std::move(fixed));
  for (const auto& h : selection.region_handles) sets.handle_vertices.push_back(h);
  if (!selection.point_handles.empty()) {
    const geometry::Connectivity conn(mesh);
    const double radius = options.point_handle_radius * bbox_diagonal(mesh.V);
    std::vector<char> claimed(static_cast<size_t>(mesh.num_vertices()), 0);
    for (int v : selection.point_handles) claimed[v] = 1;
    for (int v : selection.point_handles) {
      claimed[v] = 0;
      sets.handle_vertices.push_back(point_disc(conn, mesh, v, radius, layout, claimed));
    }
  }
  if (sets.size() < 2)
    throw InvalidArgument("mesh_deform::handle_sets(): " + std::to_string(sets.size()) +
                          " handle (the fixed region counts as one), expected at least two: the fields of one "
                          "handle are constant and give nothing to interpolate");
  return sets;
}

namespace {

// Every connected component must hold a Dirichlet vertex, or −L_ff is singular there.
void require_anchored_components(const TriMesh& mesh, const std::vector<int>& column_of) {
  const auto comps = geometry::connected_components(mesh);
  std::vector<char> anchored(static_cast<size_t>(comps.count), 0);
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (column_of[v] >= 0 && comps.vertex_component[v] >= 0) anchored[comps.vertex_component[v]] = 1;
  for (int v = 0; v < mesh.num_vertices(); ++v)
    if (const int c = comps.vertex_component[v]; c >= 0 && !anchored[c])
      throw InvalidArgument("mesh_deform::harmonic_fields(): connected component " + std::to_string(c) + " (vertex " +
                            std::to_string(v) +
                            ") holds no handle vertex and is not outside the ROI: its fields are undefined");
}

// Clamps to [0, 1] and renormalizes each row to sum 1; returns the largest overshoot.
double clamp_rows(Eigen::MatrixXd& phi) {
  double over = 0;
  for (Eigen::Index i = 0; i < phi.rows(); ++i) {
    for (Eigen::Index h = 0; h < phi.cols(); ++h) {
      double& p = phi(i, h);
      over = std::max({over, -p, p - 1.0});
      p = std::clamp(p, 0.0, 1.0);
    }
    const double sum = phi.row(i).sum();
    if (sum > 0) phi.row(i) /= sum;
  }
  return over;
}

}  // namespace

HandleFields harmonic_fields(const TriMesh& mesh, const HandleSets& sets) {
  const int n = mesh.num_vertices(), H = sets.size();
  std::vector<int> column_of(static_cast<size_t>(n), -1);
  for (int h = 0; h < H; ++h)
    for (int v : sets.handle_vertices[h]) column_of[v] = h;
  require_anchored_components(mesh, column_of);

  std::vector<int> local(static_cast<size_t>(n), -1), free;
  for (int v = 0; v < n; ++v)
    if (column_of[v] < 0) local[v] = static_cast<int>(free.size()), free.push_back(v);
  const int nf = static_cast<int>(free.size());
  const Eigen::SparseMatrix<double> L = geometry::cotan_laplacian(mesh);

  HandleFields out;
  out.phi = Eigen::MatrixXd::Zero(n, H);
  for (int v = 0; v < n; ++v)
    if (column_of[v] >= 0) out.phi(v, column_of[v]) = 1;
  if (nf > 0) {
    // −L_ff φ_f = L_fc φ_c for the first H − 1 fields: L is symmetric, so column v of L holds row v.
    std::vector<Eigen::Triplet<double>> t;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf, H - 1);
    for (int v : free)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, v); it; ++it) {
        const int u = static_cast<int>(it.row());
        if (local[u] >= 0)
          t.emplace_back(local[v], local[u], -it.value());
        else if (column_of[u] < H - 1)
          rhs(local[v], column_of[u]) += it.value();
      }
    solver::SparseMatrix A(nf, nf);
    A.setFromTriplets(t.begin(), t.end());
    auto t0 = std::chrono::steady_clock::now();
    solver::Cholesky chol;
    chol.compute(A);
    out.factorize_ms = ms_since(t0);
    out.factor_nnz = chol.report().nnz_L;
    t0 = std::chrono::steady_clock::now();
    const Eigen::MatrixXd x = chol.solve(rhs);
    out.solve_ms = ms_since(t0);
    for (int k = 0; k < nf; ++k) {
      out.phi.row(free[k]).head(H - 1) = x.row(k);
      out.phi(free[k], H - 1) = 1.0 - x.row(k).sum();
    }
    // The last field was not solved for: its Laplacian on the free vertices measures the solve.
    const Eigen::VectorXd r = L * out.phi.col(H - 1);
    double scale = 0;
    for (int v : free) out.residual = std::max(out.residual, std::abs(r(v))), scale = std::max(scale, -L.coeff(v, v));
    if (scale > 0) out.residual /= scale;
  }
  out.overshoot = clamp_rows(out.phi);
  return out;
}

Eigen::VectorXd handle_rigidity(const TriMesh& mesh, const Eigen::MatrixXd& phi) {
  const int n = mesh.num_vertices();
  Eigen::VectorXd sq = Eigen::VectorXd::Zero(n), area = Eigen::VectorXd::Zero(n);
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const Eigen::Vector3d pa = mesh.V.row(a), pb = mesh.V.row(b), pc = mesh.V.row(c);
    const Eigen::Vector3d nrm = (pb - pa).cross(pc - pa);
    const double dbl_area = nrm.norm();
    if (dbl_area <= 0) continue;
    const Eigen::Vector3d u = nrm / dbl_area;
    // ∇φ = Σ_k φ_k (u × e_k) / 2A, e_k the edge opposite corner k, counter-clockwise.
    const Eigen::Vector3d ga = u.cross(pc - pb), gb = u.cross(pa - pc), gc = u.cross(pb - pa);
    double g2 = 0;
    for (Eigen::Index h = 0; h < phi.cols(); ++h)
      g2 += ((phi(a, h) * ga + phi(b, h) * gb + phi(c, h) * gc) / dbl_area).squaredNorm();
    for (int v : {a, b, c}) sq(v) += dbl_area * g2, area(v) += dbl_area;
  }
  for (int v = 0; v < n; ++v) sq(v) = area(v) > 0 ? std::sqrt(sq(v) / area(v)) : 0.0;
  return sq;
}

}  // namespace lapis::mesh_deform
