#include "stencil.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "lapis/geometry/laplacian.h"

namespace lapis::mesh_deform {

const char* to_string(LaplacianWeights w) { return w == LaplacianWeights::Cotangent ? "cotan" : "uniform"; }

namespace detail {
namespace {

int slot(const Stencil& s, int i, int j) {
  const auto b = s.nbr.begin() + s.offsets[i], e = s.nbr.begin() + s.offsets[i + 1];
  return static_cast<int>(std::lower_bound(b, e, j) - s.nbr.begin());
}

// Bits 0..20 of x spread to bits 0, 3, 6, ..., 60 (the interleaving step of a Morton code).
uint64_t spread_bits(uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffff;
  x = (x | x << 16) & 0x1f0000ff0000ff;
  x = (x | x << 8) & 0x100f00f00f00f00f;
  x = (x | x << 4) & 0x10c30c30c30c30c3;
  x = (x | x << 2) & 0x1249249249249249;
  return x;
}

}  // namespace

std::vector<int> spatial_order(const Vertices& P) {
  const int n = static_cast<int>(P.rows());
  std::vector<std::pair<uint64_t, int>> key(static_cast<size_t>(n));
  if (n == 0) return {};
  const Eigen::RowVector3d lo = P.colwise().minCoeff(), extent = P.colwise().maxCoeff() - lo;
  const double cells = (1 << 21) - 1;
  for (int v = 0; v < n; ++v) {
    uint64_t code = 0;
    for (int a = 0; a < 3; ++a) {
      const double t = extent[a] > 0 ? (P(v, a) - lo[a]) / extent[a] : 0.0;
      code |= spread_bits(static_cast<uint64_t>(t * cells)) << a;
    }
    key[static_cast<size_t>(v)] = {code, v};
  }
  std::sort(key.begin(), key.end());  // ties (coincident cells) by index: deterministic
  std::vector<int> order(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) order[static_cast<size_t>(k)] = key[static_cast<size_t>(k)].second;
  return order;
}

std::vector<int> rank_in(const std::vector<int>& order) {
  std::vector<int> rank(order.size());
  for (size_t k = 0; k < order.size(); ++k) rank[static_cast<size_t>(order[k])] = static_cast<int>(k);
  return rank;
}

void reweight(Stencil& s, const Vertices& P, const geometry::Faces& F, LaplacianWeights weights, ObtuseAngles obtuse) {
  const int n = s.size();
  if (weights == LaplacianWeights::Uniform) {
    for (int i = 0; i < n; ++i)
      for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) s.w[k] = 1.0 / s.valence(i);
    return;
  }
  std::fill(s.w.begin(), s.w.end(), 0.0);
  for (int f = 0; f < F.rows(); ++f) {
    // Zero for a degenerate face (geometry::kDegenerateTriangleHeight): it adds nothing.
    const std::array<double, 3> cot = geometry::triangle_cotangents(P.row(F(f, 0)), P.row(F(f, 1)), P.row(F(f, 2)));
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, (c + 1) % 3), b = F(f, (c + 2) % 3);
      const double cot_c = cot[static_cast<size_t>(c)];
      const double h = 0.5 * (obtuse == ObtuseAngles::ClampToZero ? std::max(cot_c, 0.0) : cot_c);
      s.w[slot(s, a, b)] += h;
      s.w[slot(s, b, a)] += h;
    }
  }
}

Stencil make_stencil(const Vertices& P, const geometry::Faces& F, LaplacianWeights weights, ObtuseAngles obtuse) {
  const int n = static_cast<int>(P.rows());
  // Each face edge seen from both ends, bucketed by its start vertex (a counting sort: a
  // global sort of the 6·#F directed edges cost several times more), then each vertex's few
  // entries sorted and merged. An edge seen from one face only is on the boundary.
  std::vector<int> start(static_cast<size_t>(n) + 1, 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) start[static_cast<size_t>(F(f, c)) + 1] += 2;
  for (int i = 0; i < n; ++i) start[static_cast<size_t>(i) + 1] += start[static_cast<size_t>(i)];
  std::vector<int> ends(static_cast<size_t>(start[static_cast<size_t>(n)]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      ends[static_cast<size_t>(fill[static_cast<size_t>(a)]++)] = b;
      ends[static_cast<size_t>(fill[static_cast<size_t>(b)]++)] = a;
    }
  Stencil s;
  s.offsets.assign(static_cast<size_t>(n) + 1, 0);
  s.boundary.assign(static_cast<size_t>(n), 0);
  s.nbr.reserve(ends.size() / 2 + static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const auto first = ends.begin() + start[static_cast<size_t>(i)],
               last = ends.begin() + start[static_cast<size_t>(i) + 1];
    std::sort(first, last);
    for (auto k = first; k != last;) {
      auto e = k;
      while (e != last && *e == *k) ++e;
      s.nbr.push_back(*k);
      if (e - k == 1) s.boundary[static_cast<size_t>(i)] = 1;
      k = e;
    }
    s.offsets[static_cast<size_t>(i) + 1] = static_cast<int>(s.nbr.size());
  }
  s.w.assign(s.nbr.size(), 0.0);
  reweight(s, P, F, weights, obtuse);
  return s;
}

Vertices laplacian_coordinates(const Stencil& s, const Vertices& P) {
  const int n = s.size();
  Vertices D(n, 3);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    Eigen::RowVector3d d = Eigen::RowVector3d::Zero();
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) d += s.w[k] * (P.row(s.nbr[k]) - P.row(i));
    D.row(i) = d;
  }
  return D;
}

solver::SparseMatrix edge_graph(const Stencil& s) {
  const int n = s.size();
  solver::SparseMatrix E(n, n);
  E.resizeNonZeros(static_cast<Eigen::Index>(s.nbr.size()));
  std::copy(s.offsets.begin(), s.offsets.end(), E.outerIndexPtr());
  std::copy(s.nbr.begin(), s.nbr.end(), E.innerIndexPtr());  // ascending per vertex, as stencils are
  std::fill(E.valuePtr(), E.valuePtr() + E.nonZeros(), 1.0);
  return E;
}

double mean_edge_length(const Stencil& s, const Vertices& P) {
  double sum = 0;
  long count = 0;
  for (int i = 0; i < s.size(); ++i)
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
      sum += (P.row(s.nbr[k]) - P.row(i)).norm();
      ++count;
    }
  return count ? sum / count : 1.0;
}

}  // namespace detail
}  // namespace lapis::mesh_deform
