#include "lapis/geometry/laplacian.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include "lapis/core/error.h"
#include "lapis/geometry/connectivity.h"
#include "parallel.h"

namespace lapis::geometry {

std::array<double, 3> triangle_cotangents(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                          const Eigen::Vector3d& p2) {
  if (!(p0.allFinite() && p1.allFinite() && p2.allFinite()) || is_thin_triangle(p0, p1, p2, kDegenerateTriangleHeight))
    return {0, 0, 0};
  const Eigen::Vector3d p[3] = {p0, p1, p2};
  const double twice_area = (p1 - p0).cross(p2 - p0).norm();
  std::array<double, 3> cot{};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
    cot[k] = u.dot(w) / twice_area;  // |u × w| is twice the area at every corner
  }
  return cot;
}

namespace {

std::array<double, 3> corner_cotangents(const TriMesh& m, Eigen::Index f) {
  return triangle_cotangents(m.V.row(m.F(f, 0)), m.V.row(m.F(f, 1)), m.V.row(m.F(f, 2)));
}

// Assembles a symmetric vertex operator column by column, one vertex per OpenMP iteration:
// each column gathers the weights its incident faces give it, so no global triplet list
// (9 entries per face) is ever built. weight(f, k) is the weight of the face's edge opposite
// corner k; binary = true sets each off-diagonal to 1 instead of summing.
template <class Weight>
Eigen::SparseMatrix<double> assemble(const TriMesh& m, const Weight& weight, bool binary, const char* fn) {
  require_indices_in_range(m, fn);
  const int n = m.num_vertices();
  const AdjacencyLists vf = vertex_face_lists(m.F, n);
  // Column v has at most 2 |faces(v)| + 1 entries: slots in one array, compacted per column.
  using Entry = std::pair<int, double>;
  std::vector<Entry> slots(2 * vf.items.size() + static_cast<size_t>(n));
  std::vector<int> used(n);
#pragma omp parallel for schedule(dynamic, 1024) if (n >= detail::kParallelMin)
  for (int v = 0; v < n; ++v) {
    Entry* col = slots.data() + 2 * static_cast<size_t>(vf.offsets[v]) + v;
    int size = 0;
    for (int f : vf[v]) {
      int k = 0;
      while (m.F(f, k) != v) ++k;
      col[size++] = {m.F(f, (k + 1) % 3), weight(f, (k + 2) % 3)};  // edge (v, a) is opposite corner k + 2
      col[size++] = {m.F(f, (k + 2) % 3), weight(f, (k + 1) % 3)};
    }
    std::sort(col, col + size, [](const Entry& x, const Entry& y) { return x.first < y.first; });
    int out = 0;
    double diag = 0;
    for (int i = 0; i < size;) {
      int j = i;
      double w = 0;
      for (; j < size && col[j].first == col[i].first; ++j) w += col[j].second;
      if (binary) w = 1;
      diag -= w;
      col[out++] = {col[i].first, w};
      i = j;
    }
    const int at =
        static_cast<int>(std::lower_bound(col, col + out, v, [](const Entry& e, int x) { return e.first < x; }) - col);
    std::move_backward(col + at, col + out, col + out + 1);
    col[at] = {v, diag};
    used[v] = out + 1;
  }
  Eigen::SparseMatrix<double> L(n, n);
  int* outer = L.outerIndexPtr();
  outer[0] = 0;
  for (int v = 0; v < n; ++v) outer[v + 1] = outer[v] + used[v];
  L.resizeNonZeros(outer[n]);
#pragma omp parallel for schedule(static) if (n >= detail::kParallelMin)
  for (int v = 0; v < n; ++v) {
    const Entry* col = slots.data() + 2 * static_cast<size_t>(vf.offsets[v]) + v;
    for (int i = 0; i < used[v]; ++i) {
      L.innerIndexPtr()[outer[v] + i] = col[i].first;
      L.valuePtr()[outer[v] + i] = col[i].second;
    }
  }
  return L;
}

}  // namespace

Eigen::SparseMatrix<double> cotan_laplacian(const TriMesh& mesh) {
  std::vector<std::array<double, 3>> cot(mesh.num_faces());
  const auto weight = [&](int f, int k) { return 0.5 * cot[f][k]; };
  require_indices_in_range(mesh, "geometry::cotan_laplacian()");
#pragma omp parallel for schedule(static) if (mesh.num_faces() >= detail::kParallelMin)
  for (int f = 0; f < mesh.num_faces(); ++f) cot[f] = corner_cotangents(mesh, f);
  return assemble(mesh, weight, false, "geometry::cotan_laplacian()");
}

Eigen::SparseMatrix<double> uniform_laplacian(const TriMesh& mesh) {
  return assemble(
      mesh, [](int, int) { return 1.0; }, true, "geometry::uniform_laplacian()");
}

Eigen::VectorXd vertex_areas(const TriMesh& mesh, MassType type) {
  require_indices_in_range(mesh, "geometry::vertex_areas()");
  Eigen::VectorXd area = Eigen::VectorXd::Zero(mesh.num_vertices());
  for (int f = 0; f < mesh.num_faces(); ++f) {
    const Eigen::Vector3d p[3] = {mesh.V.row(mesh.F(f, 0)), mesh.V.row(mesh.F(f, 1)), mesh.V.row(mesh.F(f, 2))};
    const double A = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    std::array<double, 3> share{A / 3, A / 3, A / 3};
    // A degenerate face (all cotangents zero) keeps the barycentric thirds of its ~zero area.
    const std::array<double, 3> cot = type == MassType::Voronoi ? corner_cotangents(mesh, f) : std::array<double, 3>{};
    if (cot != std::array<double, 3>{}) {
      const int obtuse = cot[0] < 0 ? 0 : cot[1] < 0 ? 1 : cot[2] < 0 ? 2 : -1;
      for (int k = 0; k < 3; ++k) {
        if (obtuse >= 0) {
          share[k] = k == obtuse ? A / 2 : A / 4;
        } else {
          // Voronoi region of corner k: 1/8 (|k,k+1|^2 cot(k+2) + |k,k+2|^2 cot(k+1)).
          const int i = (k + 1) % 3, j = (k + 2) % 3;
          share[k] = 0.125 * ((p[i] - p[k]).squaredNorm() * cot[j] + (p[j] - p[k]).squaredNorm() * cot[i]);
        }
      }
    }
    for (int k = 0; k < 3; ++k) area[mesh.F(f, k)] += share[k];
  }
  return area;
}

Eigen::SparseMatrix<double> mass_matrix(const TriMesh& mesh, MassType type) {
  const Eigen::VectorXd a = vertex_areas(mesh, type);
  Eigen::SparseMatrix<double> M(a.size(), a.size());
  M.reserve(Eigen::VectorXi::Ones(a.size()));
  for (Eigen::Index i = 0; i < a.size(); ++i) M.insert(i, i) = a[i];
  M.makeCompressed();
  return M;
}

Eigen::SparseMatrix<double> normalized_cotan_laplacian(const TriMesh& mesh, MassType type) {
  Eigen::SparseMatrix<double> L = cotan_laplacian(mesh);
  const Eigen::VectorXd a = vertex_areas(mesh, type);
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (!(a[i] > 0) && L.col(i).nonZeros() > 0)
      throw InvalidArgument("geometry::normalized_cotan_laplacian(): vertex " + std::to_string(i) +
                            " has zero area, expected non-degenerate faces around it");
  const Eigen::VectorXd inv = a.unaryExpr([](double x) { return x > 0 ? 1.0 / x : 0.0; });
  return inv.asDiagonal() * L;
}

Eigen::MatrixX3d laplacian_coordinates(const Eigen::SparseMatrix<double>& L, const Vertices& V) {
  if (L.cols() != V.rows() || L.rows() != V.rows())
    throw InvalidArgument("geometry::laplacian_coordinates(): L is " + std::to_string(L.rows()) + " x " +
                          std::to_string(L.cols()) + ", expected " + std::to_string(V.rows()) + " x " +
                          std::to_string(V.rows()));
  return L * V;
}

Eigen::MatrixX3d laplacian_coordinates(const TriMesh& mesh) {
  return laplacian_coordinates(cotan_laplacian(mesh), mesh.V);
}

}  // namespace lapis::geometry
