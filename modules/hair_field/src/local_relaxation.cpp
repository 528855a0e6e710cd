#include "local_relaxation.h"

#include <algorithm>
#include <cstddef>

namespace lapis::hair_field::detail {
namespace {

// A node's grid position and its 6-neighbours (those inside the grid).
struct Node {
  int i, j, k;
  int count;             // |N(v)|
  std::ptrdiff_t nb[6];  // neighbour indices
};

inline Node node_at(const std::array<int, 3>& d, std::ptrdiff_t v) {
  const std::ptrdiff_t sy = d[0], sz = static_cast<std::ptrdiff_t>(d[0]) * d[1];
  Node n;
  n.i = static_cast<int>(v % d[0]);
  n.j = static_cast<int>((v / d[0]) % d[1]);
  n.k = static_cast<int>(v / sz);
  n.count = 0;
  if (n.i > 0) n.nb[n.count++] = v - 1;
  if (n.i + 1 < d[0]) n.nb[n.count++] = v + 1;
  if (n.j > 0) n.nb[n.count++] = v - sy;
  if (n.j + 1 < d[1]) n.nb[n.count++] = v + sy;
  if (n.k > 0) n.nb[n.count++] = v - sz;
  if (n.k + 1 < d[2]) n.nb[n.count++] = v + sz;
  return n;
}

// (D x)_u = −x_u + Σ_{j∈N(u)} x_j / |N(u)|, 3 columns; n = node_at(d, u).
inline void laplacian_at(const Node& n, std::ptrdiff_t u, const double* x, double out[3]) {
  double s[3] = {0, 0, 0};
  for (int a = 0; a < n.count; ++a)
    for (int c = 0; c < 3; ++c) s[c] += x[3 * n.nb[a] + c];
  for (int c = 0; c < 3; ++c) out[c] = s[c] / n.count - x[3 * u + c];
}

// Every node within two steps of v has six neighbours.
inline bool interior(const std::array<int, 3>& d, const Node& n) {
  return n.i >= 2 && n.i + 2 < d[0] && n.j >= 2 && n.j + 2 < d[1] && n.k >= 2 && n.k + 2 < d[2];
}

// Row v of DᵀD without its diagonal, applied to x, at an interior node: there DᵀD = L²/36
// with L the 7-point Laplacian (centre −6), i.e. 42 at the centre, −12 at the faces, 2 at
// the 12 edge neighbours and 1 two steps along an axis, all / 36. Returns (DᵀD)_vv.
inline double off_diagonal_interior(const std::array<int, 3>& d, std::ptrdiff_t v, const double* x, double sum[3]) {
  const std::ptrdiff_t o[3] = {1, d[0], static_cast<std::ptrdiff_t>(d[0]) * d[1]};
  double faces[3] = {0, 0, 0}, edges[3] = {0, 0, 0}, axial[3] = {0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    for (int c = 0; c < 3; ++c) {
      faces[c] += x[3 * (v + o[a]) + c] + x[3 * (v - o[a]) + c];
      axial[c] += x[3 * (v + 2 * o[a]) + c] + x[3 * (v - 2 * o[a]) + c];
    }
    for (int b = a + 1; b < 3; ++b)
      for (int c = 0; c < 3; ++c)
        edges[c] += x[3 * (v + o[a] + o[b]) + c] + x[3 * (v + o[a] - o[b]) + c] + x[3 * (v - o[a] + o[b]) + c] +
                    x[3 * (v - o[a] - o[b]) + c];
  }
  for (int c = 0; c < 3; ++c) sum[c] = (-12 * faces[c] + 2 * edges[c] + axial[c]) / 36;
  return 42.0 / 36;
}

// The same anywhere, from D itself: (DᵀD x)_v = −(D x)_v + Σ_{u∈N(v)} (D x)_u / |N(u)| and
// (DᵀD)_vv = 1 + Σ_{u∈N(v)} 1/|N(u)|².
inline double off_diagonal(const std::array<int, 3>& d, std::ptrdiff_t v, const double* x, double sum[3]) {
  const Node n = node_at(d, v);
  double own[3];
  laplacian_at(n, v, x, own);
  double diag = 1;
  for (int c = 0; c < 3; ++c) sum[c] = -own[c];
  for (int a = 0; a < n.count; ++a) {
    const std::ptrdiff_t u = n.nb[a];
    const Node nu = node_at(d, u);
    const int count = nu.count;
    double lu[3];
    laplacian_at(nu, u, x, lu);
    for (int c = 0; c < 3; ++c) sum[c] += lu[c] / count;
    diag += 1.0 / (static_cast<double>(count) * count);
  }
  for (int c = 0; c < 3; ++c) sum[c] -= diag * x[3 * v + c];
  return diag;
}

}  // namespace

std::vector<int> nodes_near(const std::array<int, 3>& d, std::span<const int> seeds, int radius,
                            std::vector<char>& mark) {
  std::vector<int> nodes;
  for (int s : seeds) {
    const Node n = node_at(d, s);
    for (int k = std::max(0, n.k - radius); k <= std::min(d[2] - 1, n.k + radius); ++k)
      for (int j = std::max(0, n.j - radius); j <= std::min(d[1] - 1, n.j + radius); ++j)
        for (int i = std::max(0, n.i - radius); i <= std::min(d[0] - 1, n.i + radius); ++i) {
          const int v = i + d[0] * (j + d[1] * k);
          if (!mark[v]) mark[v] = 1, nodes.push_back(v);
        }
  }
  for (int v : nodes) mark[v] = 0;
  std::sort(nodes.begin(), nodes.end());
  return nodes;
}

void gauss_seidel(const std::array<int, 3>& d, const double* w, const double* c, std::span<const int> nodes, int sweeps,
                  double* x) {
  // Which rows take the interior stencil, found once (the sweeps then divide nothing).
  std::vector<char> inner(nodes.size());
  for (size_t a = 0; a < nodes.size(); ++a) inner[a] = interior(d, node_at(d, nodes[a]));
  for (int sweep = 0; sweep < sweeps; ++sweep)
    for (size_t a = 0; a < nodes.size(); ++a) {
      const int v = nodes[a];
      double sum[3];
      const double diag = (inner[a] ? off_diagonal_interior(d, v, x, sum) : off_diagonal(d, v, x, sum)) + w[v];
      const std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(v);
      for (int k = 0; k < 3; ++k) x[f + k] = (w[v] * c[f + k] - sum[k]) / diag;
    }
}

}  // namespace lapis::hair_field::detail
