#include "implicit_first_system.h"

#include <algorithm>
#include <utility>

#include "sparse_rows.h"

namespace lapis::mesh_deform::detail {
namespace {

// The metric of E_R: the Laplacian of the pair graph (degree on the diagonal, −1 per pair)
// over `slots` vertices, ⊗ I₃ (rows 3s + a, a = x y z). Written column by column: the same
// matrix from ~1M pairs as setFromTriplets on their 12 triplets each took 2–3× longer, most of
// it allocating and sorting the 12M triplets. Each pair appears once.
solver::SparseMatrix pair_graph_laplacian(int slots, const std::vector<std::pair<int, int>>& pairs) {
  std::vector<int> start(static_cast<size_t>(slots) + 1, 0);
  for (const auto& [a, b] : pairs) ++start[a + 1], ++start[b + 1];
  for (int v = 0; v < slots; ++v) start[v + 1] += start[v];
  std::vector<int> adjacent(static_cast<size_t>(start[slots]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (const auto& [a, b] : pairs) adjacent[fill[a]++] = b, adjacent[fill[b]++] = a;
  const std::ptrdiff_t entries = 3 * (static_cast<std::ptrdiff_t>(start[slots]) + slots);
  solver::SparseMatrix M(3 * slots, 3 * slots);
  M.resizeNonZeros(entries);
  int* outer = M.outerIndexPtr();
  int* inner = M.innerIndexPtr();
  double* value = M.valuePtr();
  std::ptrdiff_t at = 0;
  for (int v = 0; v < slots; ++v) {
    int* first = adjacent.data() + start[v];
    int* last = adjacent.data() + start[v + 1];
    std::sort(first, last);
    const int* diagonal = std::lower_bound(first, last, v);
    const double degree = static_cast<double>(last - first);
    for (int a = 0; a < 3; ++a) {
      outer[3 * v + a] = static_cast<int>(at);
      for (const int* u = first; u != last; ++u) {
        if (u == diagonal) inner[at] = 3 * v + a, value[at++] = degree;
        inner[at] = 3 * *u + a, value[at++] = -1.0;
      }
      if (diagonal == last) inner[at] = 3 * v + a, value[at++] = degree;
    }
  }
  outer[3 * slots] = static_cast<int>(at);
  return M;
}

// Does M_i depend on a free unknown? Terms that do not are constants and left out.
std::vector<char> touching_free(const WorkMesh& w, const GradientStencils& G) {
  const int n = w.mesh.num_vertices();
  std::vector<char> touches(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i)
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k)
      if (w.role[G.vertex[k]] == VertexRole::Free) touches[i] = 1;
  return touches;
}

// E_L (Eq. 2.6): D(ṽ_i) − M_i δ_i, one row per free vertex and coordinate.
solver::SparseMatrix laplacian_rows(const Stencil& s, const GradientStencils& G, const Vertices& deltaP,
                                    const std::vector<int>& free, int n) {
  SparseRows EL(n);
  for (int i : free) {
    add_laplacian_row(EL, s, i);
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) EL.add(G.vertex[k], -G.g[k].dot(deltaP.row(i)));
  }
  return EL.matrix();
}

// E_R (Eq. 2.7): Σ ‖M_i − M_j‖² over pairs within 2 rings (footnote 1). M_i's rows are
// linear in the positions (the gradient stencil g_i), so E_R = Σ_a xᵀ G_aᵀ (Dᵀ D) G_a x with
// D the pairs' incidence matrix: three rows g_i(a) per vertex in a pair, measured in the
// metric Dᵀ D ⊗ I₃ (the pair graph's Laplacian), rather than three rows g_i(a) − g_j(a) per
// pair — the same energy from a normal matrix that costs several times less to assemble.
void coherence_rows(const WorkMesh& w, const Stencil& s, const GradientStencils& G, const std::vector<char>& touches,
                    FirstSystemRows& out) {
  const int n = w.mesh.num_vertices();
  SparseRows ER(n);
  std::vector<int> slot(static_cast<size_t>(n), -1);  // vertex → its three rows / 3
  std::vector<std::pair<int, int>> pairs;             // slots of the vertices of each pair
  auto slot_of = [&](int i) {
    if (slot[i] < 0) {
      slot[i] = ER.rows() / 3;
      for (int a = 0; a < 3; ++a) {
        ER.begin_row();
        for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) ER.add(G.vertex[k], G.g[k](a));
      }
    }
    return slot[i];
  };
  std::vector<int> stamp(static_cast<size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    if (!w.active[i]) continue;
    stamp[i] = i;
    auto visit = [&](int j) {
      if (stamp[j] == i) return;
      stamp[j] = i;
      if (j < i || !w.active[j] || !(touches[i] || touches[j])) return;
      const int si = slot_of(i);
      pairs.emplace_back(si, slot_of(j));
    };
    for (int k = s.offsets[i]; k < s.offsets[i + 1]; ++k) {
      const int j = s.nbr[k];
      visit(j);
      for (int l = s.offsets[j]; l < s.offsets[j + 1]; ++l) visit(s.nbr[l]);
    }
  }
  out.coherence = ER.matrix();
  out.coherence_metric = ER.rows() > 0 ? pair_graph_laplacian(ER.rows() / 3, pairs) : solver::SparseMatrix(0, 0);
}

// Eq. 2.8 transformation constraints: region handles carry their transform's linear part,
// the border of the fixed region the identity. Point handles constrain positions only.
void transform_rows(const WorkMesh& w, const GradientStencils& G, const std::vector<char>& touches,
                    const std::vector<int>& constrained, FirstSystemRows& out) {
  SparseRows T(w.mesh.num_vertices());
  for (int c : constrained) {
    if (!w.active[c] || !touches[c] || w.role[c] == VertexRole::PointHandle) continue;
    out.transform_vertex.push_back(c);
    out.transform_handle.push_back(w.role[c] == VertexRole::RegionHandle ? w.handle_of[c] : -1);
    for (int a = 0; a < 3; ++a) {
      T.begin_row();
      for (int k = G.offsets[c]; k < G.offsets[c + 1]; ++k) T.add(G.vertex[k], G.g[k](a));
    }
  }
  out.transform = T.matrix();
}

// E_T (§3.3.3): row M_i δ_i − Σ_j b_j M_j δ_j, linear in the unknowns like E_L's M_i δ_i.
solver::SparseMatrix blend_rows(const GradientStencils& G, const Vertices& deltaP, const std::vector<char>& touches,
                                const std::vector<LaplacianBlend>& blends, int n) {
  SparseRows EB(n);
  auto add_transformed = [&](int i, double b) {
    for (int k = G.offsets[i]; k < G.offsets[i + 1]; ++k) EB.add(G.vertex[k], b * G.g[k].dot(deltaP.row(i)));
  };
  for (const LaplacianBlend& t : blends) {
    bool defined = G.offsets[t.vertex] < G.offsets[t.vertex + 1], free = touches[t.vertex];
    for (int j : t.others) defined = defined && G.offsets[j] < G.offsets[j + 1], free = free || touches[j];
    if (!defined || !free) continue;
    EB.begin_row();
    add_transformed(t.vertex, 1.0);
    for (int k = 0; k < 3; ++k)
      if (t.weights[k] != 0) add_transformed(t.others[k], -t.weights[k]);
  }
  return EB.matrix();
}

}  // namespace

FirstSystemRows first_system_rows(const WorkMesh& w, const Stencil& s, const GradientStencils& G,
                                  const Vertices& deltaP, const std::vector<int>& free,
                                  const std::vector<int>& constrained, const std::vector<LaplacianBlend>& blends) {
  const int n = w.mesh.num_vertices();
  const std::vector<char> touches = touching_free(w, G);
  FirstSystemRows out;
  out.laplacian = laplacian_rows(s, G, deltaP, free, n);
  coherence_rows(w, s, G, touches, out);
  transform_rows(w, G, touches, constrained, out);
  out.blend = blend_rows(G, deltaP, touches, blends, n);
  return out;
}

}  // namespace lapis::mesh_deform::detail
