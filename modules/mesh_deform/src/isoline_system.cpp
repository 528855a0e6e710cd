#include "isoline_system.h"

#include <algorithm>

#include "lapis/core/parallel_for.h"

namespace lapis::mesh_deform::detail {
namespace {

using solver::DenseMatrix;

// A sparse 4m-vector of 4-blocks: the row of L W_x at one vertex.
struct BlockRow {
  std::vector<Eigen::Vector4d> value;  // 4m/4 blocks
  std::vector<int> touched;
  std::vector<char> used;

  explicit BlockRow(int m) : value(static_cast<size_t>(m), Eigen::Vector4d::Zero()), used(static_cast<size_t>(m), 0) {}
  void add(int l, const Eigen::Vector4d& v) {
    if (!used[l]) used[l] = 1, touched.push_back(l);
    value[l] += v;
  }
  void clear() {
    for (int l : touched) value[l].setZero(), used[l] = 0;
    touched.clear();
  }
};

// One partial result per thread over the vertices [0, n): each is a dense matrix of the size of
// the reduced system, so chunks are few and large. body(lo, hi, partial) fills its partial.
template <class T, class Body>
std::vector<T> per_thread_partials(int n, Body body) {
  const int threads = std::max(1, core::parallel_threads());
  const std::ptrdiff_t grain = std::max<std::ptrdiff_t>(1, (n + threads - 1) / threads);
  std::vector<T> partial(static_cast<size_t>((n + grain - 1) / grain));
  core::parallel_for(0, n, grain, [&](std::ptrdiff_t lo, std::ptrdiff_t hi) {
    body(lo, hi, partial[static_cast<size_t>(lo / grain)]);
  });
  return partial;
}

struct Partial {
  DenseMatrix lap, P;
};

// Rows [lo, hi) of (L W_x)ᵀ(L W_x) (upper block triangle) and (L W_x)ᵀ W_δ.
void accumulate_rows(const IsolineBasis& b, const Eigen::SparseMatrix<double>& L, const geometry::Vertices& delta,
                     std::ptrdiff_t lo, std::ptrdiff_t hi, Partial& out) {
  const int m = b.count();
  BlockRow row(m);
  for (std::ptrdiff_t k = lo; k < hi; ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, k); it; ++it) {
      const int j = static_cast<int>(it.row());
      const Eigen::Vector4d h = it.value() * b.homogeneous(j);
      for (int i = 0; i < b.sets; ++i) {
        const int s = b.slot(j, i);
        if (b.w0[s] != 0) row.add(b.lower[s], b.w0[s] * h);
        if (b.w1[s] != 0) row.add(b.lower[s] + 1, b.w1[s] * h);
      }
    }
    const Eigen::RowVector3d d = delta.row(k);
    for (int la : row.touched) {
      for (int lb : row.touched)
        if (la <= lb) out.lap.block<4, 4>(4 * la, 4 * lb).noalias() += row.value[la] * row.value[lb].transpose();
      for (int i = 0; i < b.sets; ++i) {
        const int s = b.slot(static_cast<int>(k), i);
        out.P.block<4, 3>(4 * la, 3 * b.lower[s]).noalias() += row.value[la] * (b.w0[s] * d);
        out.P.block<4, 3>(4 * la, 3 * b.lower[s] + 3).noalias() += row.value[la] * (b.w1[s] * d);
      }
    }
    row.clear();
  }
}

// Mirrors the upper block triangle into the lower.
void symmetrize_blocks(DenseMatrix& A) {
  const DenseMatrix T = A.transpose();
  A.triangularView<Eigen::StrictlyLower>() = T.triangularView<Eigen::StrictlyLower>();
}

void add_handle_group(const IsolineBasis& b, const HandleGroup& g, IsolineSystem& sys, DenseMatrix& Gg) {
  for (int v : g.vertices) {
    const Eigen::Vector4d h = b.homogeneous(v);
    const Eigen::Matrix4d hh = h * h.transpose();
    for (int i = 0; i < b.sets; ++i) {
      const int s = b.slot(v, i);
      const int l[2] = {b.lower[s], b.lower[s] + 1};
      const double w[2] = {b.w0[s], b.w1[s]};
      for (int p = 0; p < 2; ++p) {
        if (g.affine)
          Gg.middleRows<4>(4 * l[p]) += w[p] * hh;
        else
          Gg.middleRows<4>(4 * l[p]) += w[p] * h;
        for (int q = 0; q < b.sets; ++q) {
          const int t = b.slot(v, q);
          sys.handles.block<4, 4>(4 * l[p], 4 * b.lower[t]) += w[p] * b.w0[t] * hh;
          sys.handles.block<4, 4>(4 * l[p], 4 * b.lower[t] + 4) += w[p] * b.w1[t] * hh;
        }
      }
    }
  }
}

// Eq. 5: r_{i,j} − r_{i,j+1} = 0 on every entry, as MᵀM.
DenseMatrix smoothness_normal_matrix(const IsolineBasis& b) {
  const int m = b.count();
  DenseMatrix S = DenseMatrix::Zero(4 * m, 4 * m);
  for (int i = 0; i < b.sets; ++i)
    for (int j = 0; j + 1 < b.isolines; ++j) {
      const int a = 4 * (i * b.isolines + j), c = a + 4;
      S.block<4, 4>(a, a).diagonal().array() += 1;
      S.block<4, 4>(c, c).diagonal().array() += 1;
      S.block<4, 4>(a, c).diagonal().array() -= 1;
      S.block<4, 4>(c, a).diagonal().array() -= 1;
    }
  return S;
}

}  // namespace

IsolineSystem assemble_isoline_system(const IsolineBasis& b, const Eigen::SparseMatrix<double>& L,
                                      const geometry::Vertices& delta, const std::vector<HandleGroup>& groups) {
  const int m = b.count(), n = b.vertices;
  const auto partial = per_thread_partials<Partial>(n, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, Partial& p) {
    p.lap = DenseMatrix::Zero(4 * m, 4 * m);
    p.P = DenseMatrix::Zero(4 * m, 3 * m);
    accumulate_rows(b, L, delta, lo, hi, p);
  });
  IsolineSystem sys;
  sys.laplacian = DenseMatrix::Zero(4 * m, 4 * m);
  sys.P = DenseMatrix::Zero(4 * m, 3 * m);
  for (const Partial& p : partial) sys.laplacian += p.lap, sys.P += p.P;
  symmetrize_blocks(sys.laplacian);

  sys.handles = DenseMatrix::Zero(4 * m, 4 * m);
  for (const HandleGroup& g : groups) {
    DenseMatrix Gg = DenseMatrix::Zero(4 * m, g.affine ? 4 : 1);
    add_handle_group(b, g, sys, Gg);
    sys.G.push_back(std::move(Gg));
    sys.handle_rows += static_cast<int>(g.vertices.size());
  }
  sys.smoothness = smoothness_normal_matrix(b);
  return sys;
}

DenseMatrix basis_transpose_times(const IsolineBasis& b, const geometry::Vertices& Y) {
  const int m = b.count(), n = b.vertices;
  const auto partial = per_thread_partials<DenseMatrix>(n, [&](std::ptrdiff_t lo, std::ptrdiff_t hi, DenseMatrix& p) {
    p = DenseMatrix::Zero(4 * m, 3);
    for (std::ptrdiff_t k = lo; k < hi; ++k) {
      const Eigen::Matrix<double, 4, 3> hy = b.homogeneous(static_cast<int>(k)) * Y.row(k);
      for (int i = 0; i < b.sets; ++i) {
        const int s = b.slot(static_cast<int>(k), i);
        p.middleRows<4>(4 * b.lower[s]) += b.w0[s] * hy;
        p.middleRows<4>(4 * b.lower[s] + 4) += b.w1[s] * hy;
      }
    }
  });
  DenseMatrix out = DenseMatrix::Zero(4 * m, 3);
  for (const DenseMatrix& p : partial) out += p;
  return out;
}

}  // namespace lapis::mesh_deform::detail
