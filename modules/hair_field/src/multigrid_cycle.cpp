// The multigrid cycle on the hierarchy (multigrid_hierarchy.h): residuals, Chebyshev–Jacobi
// smoothing fused with the products it needs, restriction, prolongation and the coarsest
// dense solve, and apply(), the preconditioner the field solver calls once per iteration.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "grid_stencil.h"
#include "grid_transfer.h"
#include "multigrid_hierarchy.h"

namespace lapis::hair_field::detail {
namespace {

enum class Mode { Assign, Add, Subtract };

// y = A x, y += A x or y -= A x, 3 columns at once.
void spmv(const RowSparseF& A, const FieldF& x, FieldF& y, Mode mode) {
  const int n = static_cast<int>(A.rows());
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const Real* val = A.valuePtr();
  const Real* xp = x.data();
  Real* yp = y.data();
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s0 = 0, s1 = 0, s2 = 0;
    for (int p = outer[i]; p < outer[i + 1]; ++p) {
      const Real v = val[p];
      const Real* xc = xp + 3 * static_cast<std::ptrdiff_t>(inner[p]);
      s0 += v * xc[0];
      s1 += v * xc[1];
      s2 += v * xc[2];
    }
    Real* yi = yp + 3 * static_cast<std::ptrdiff_t>(i);
    if (mode == Mode::Subtract) {
      yi[0] -= s0, yi[1] -= s1, yi[2] -= s2;
    } else if (mode == Mode::Add) {
      yi[0] += s0, yi[1] += s1, yi[2] += s2;
    } else {
      yi[0] = s0, yi[1] = s1, yi[2] = s2;
    }
  }
}

// Four floats as one SSE register (GCC/Clang vector extension): the compiler did not
// vectorize the 3-column gather loop by itself.
typedef Real Real4 __attribute__((vector_size(4 * sizeof(Real))));

inline Real4 load4(const Real* p) {
  Real4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// s[0..2] = (A u)_i, 3 columns. A row has up to 125 entries. Where the row's last column
// is not the vector's last node, an entry's 3 values are read as 4 (the 4th belongs to the
// next node and is ignored) and multiplied and added as one vector, in two partial sums so
// consecutive entries do not wait for each other's addition.
inline void row_product(const RowSparseF& A, const Real* u, int i, Real s[4]) {
  const int* inner = A.innerIndexPtr();
  const Real* val = A.valuePtr();
  const int begin = A.outerIndexPtr()[i], end = A.outerIndexPtr()[i + 1];
  Real4 a0 = {0, 0, 0, 0}, a1 = {0, 0, 0, 0};
  int p = begin;
  if (end > begin && inner[end - 1] + 1 < A.cols()) {
    for (; p + 2 <= end; p += 2) {
      a0 += val[p] * load4(u + 3 * static_cast<std::ptrdiff_t>(inner[p]));
      a1 += val[p + 1] * load4(u + 3 * static_cast<std::ptrdiff_t>(inner[p + 1]));
    }
  }
  a0 += a1;
  for (int k = 0; k < 4; ++k) s[k] = a0[k];
  for (; p < end; ++p) {
    const Real v = val[p];
    const Real* uc = u + 3 * static_cast<std::ptrdiff_t>(inner[p]);
    for (int k = 0; k < 3; ++k) s[k] += v * uc[k];
  }
}

// y += x.
void add(const FieldF& x, FieldF& y) {
  const std::ptrdiff_t size = x.size();
  const Real* xp = x.data();
  Real* yp = y.data();
#pragma omp parallel for schedule(static) if (size > 3 * parallel_nodes)
  for (std::ptrdiff_t f = 0; f < size; ++f) yp[f] += xp[f];
}

// r = b − A x on a sparse level.
void sparse_residual(const RowSparseF& A, const Real* x, const Real* b, Real* r) {
  const int n = static_cast<int>(A.rows());
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s[4];
    row_product(A, x, i, s);
    for (std::ptrdiff_t k = 0; k < 3; ++k) r[3 * i + k] = b[3 * i + k] - s[k];
  }
}

// One Chebyshev step on a sparse level fused with the product before it, in one pass:
//   r_out = r_in − A u,  d_new = a d + c D⁻¹ r_out,  x += d_new (+ d when add_d).
// u is d, except in the first step of a smoothing from a non-zero x, where u is x itself:
// that step may not write x while other rows still gather from it, so it passes
// x = nullptr and the next step adds both corrections (add_d). d_new is a separate buffer
// for the same reason. d may be nullptr when a = 0.
void sparse_chebyshev_step(const RowSparseF& A, const Real* u, const Real* d, Real* d_new, Real* x, bool add_d,
                           const Real* r_in, Real* r_out, const VectorR& inv_diag, Real a, Real c) {
  const int n = static_cast<int>(A.rows());
#pragma omp parallel for schedule(static) if (A.nonZeros() > parallel_nonzeros)
  for (int i = 0; i < n; ++i) {
    Real s[4];
    row_product(A, u, i, s);
    const Real ci = c * inv_diag[i];
    for (int k = 0; k < 3; ++k) {
      const std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i) + k;
      const Real r = r_in[f] - s[k];
      r_out[f] = r;
      const Real dn = (d ? a * d[f] : Real(0)) + ci * r;
      d_new[f] = dn;
      if (x) x[f] += add_d ? dn + d[f] : dn;
    }
  }
}

}  // namespace

void MultigridHierarchy::residual(Level& L) {
  const Real* b = L.b.data();
  Real* r = L.r.data();
  if (L.matrix_free) {
    // Zero at the pinned nodes: the residual only goes to the restriction, whose columns
    // there are zero (grid_transfer.h relies on it).
    const char* pinned = pinned_.data();
    normal_operator_visit(L.dims, L.weights.data(), L.x.data(), L.buffers,
                          [&](std::ptrdiff_t f0, std::ptrdiff_t len, const Real* v) {
                            for (std::ptrdiff_t f = 0; f < len; ++f) r[f0 + f] = b[f0 + f] - v[f];
                            const char* pin = pinned + f0 / 3;
                            for (std::ptrdiff_t i = 0; i < len / 3; ++i)
                              if (pin[i]) r[f0 + 3 * i] = r[f0 + 3 * i + 1] = r[f0 + 3 * i + 2] = 0;
                          });
  } else {
    sparse_residual(L.Af, L.x.data(), L.b.data(), L.r.data());
  }
}

void MultigridHierarchy::chebyshev_step(Level& L, bool from_x, bool& pending, const Real* r_in, Real a, Real c,
                                        bool last, bool post) {
  Real* r = L.r.data();
  if (L.matrix_free) {
    // The matrix-free apply's second pass reads its operand only on the line it visits, so
    // the step updates d (or x) in place, a line at a time. The last step of a smoothing
    // stores neither r nor d, which nothing reads before they are next written; the last
    // step of the cycle also forms the caller's dot products with z (apply()).
    Real* x = L.x.data();
    Real* d = L.d.data();
    const Real* inv = L.inv_diag3.data();
    const bool dot = last && post && dot_with_ != nullptr && &L == &levels_.front();
    if (dot) dot_done_ = true;
    normal_operator_visit(L.dims, L.weights.data(), from_x ? x : d, L.buffers,
                          [&](std::ptrdiff_t f0, std::ptrdiff_t len, const Real* v) {
                            Real* xl = x + f0;
                            Real* dl = d + f0;
                            Real* rl = r + f0;
                            const Real* rin = r_in + f0;
                            const Real* il = inv + f0;
                            if (last) {
                              const Real da = from_x ? Real(0) : a;
                              for (std::ptrdiff_t f = 0; f < len; ++f)
                                xl[f] += da * dl[f] + c * il[f] * (rin[f] - v[f]);
                              if (dot) {
                                const double* wl = dot_with_ + f0;
                                double* acc = dot_partials_.data() + 8 * omp_get_thread_num();
                                for (std::ptrdiff_t f = 0; f < len; f += 3)
                                  for (int k = 0; k < 3; ++k) acc[k] += wl[f + k] * static_cast<double>(xl[f + k]);
                              }
                            } else if (from_x) {
                              for (std::ptrdiff_t f = 0; f < len; ++f) {
                                rl[f] = rin[f] - v[f];
                                dl[f] = c * il[f] * rl[f];
                                xl[f] += dl[f];
                              }
                            } else {
                              for (std::ptrdiff_t f = 0; f < len; ++f) {
                                rl[f] = rin[f] - v[f];
                                dl[f] = a * dl[f] + c * il[f] * rl[f];
                                xl[f] += dl[f];
                              }
                            }
                          });
    return;
  }
  if (from_x) {
    sparse_chebyshev_step(L.Af, L.x.data(), nullptr, L.d.data(), nullptr, false, r_in, r, L.inv_diag, 0, c);
    pending = true;
    return;
  }
  sparse_chebyshev_step(L.Af, L.d.data(), L.d.data(), L.d2.data(), L.x.data(), pending, r_in, r, L.inv_diag, a, c);
  L.d.swap(L.d2);
  pending = false;
}

void MultigridHierarchy::smooth(Level& L, bool zero_initial) {
  // Chebyshev iteration on D⁻¹A over [lmin, lmax] (Adams, Brezina, Hu, Tuminaro 2003).
  // Each step is one pass fused with the operator apply before it (chebyshev_step); the
  // residual is only ever stored, never copied: the first step reads b.
  const Real lmax = L.lambda_max, lmin = static_cast<Real>(opt_.smoothing_range) * lmax;
  const Real theta = Real(0.5) * (lmax + lmin), delta = Real(0.5) * (lmax - lmin);
  const Real sigma = theta / delta;
  Real rho = Real(1) / sigma;
  const Real* r_in = L.b.data();
  bool pending = false;
  if (zero_initial) {
    // From x = 0 the residual is b: x = d = D⁻¹ b / θ, no operator apply.
    const int n = static_cast<int>(L.x.rows());
    const Real* b = L.b.data();
    Real* x = L.x.data();
    Real* d = L.d.data();
    const Real c = 1 / theta;
#pragma omp parallel for schedule(static) if (n > parallel_nodes)
    for (int i = 0; i < n; ++i) {
      const Real ci = c * L.inv_diag[i];
      for (std::ptrdiff_t f = 3 * static_cast<std::ptrdiff_t>(i); f < 3 * i + 3; ++f) x[f] = d[f] = ci * b[f];
    }
  } else {
    chebyshev_step(L, true, pending, r_in, 0, 1 / theta, opt_.smoothing_degree == 1, true);
    r_in = L.r.data();
  }
  for (int it = 1; it < opt_.smoothing_degree; ++it) {
    const Real rho_new = Real(1) / (Real(2) * sigma - rho);
    chebyshev_step(L, false, pending, r_in, rho_new * rho, Real(2) * rho_new / delta, it + 1 == opt_.smoothing_degree,
                   !zero_initial);
    r_in = L.r.data();
    rho = rho_new;
  }
  if (pending) L.x += L.d;  // degree 1 from a non-zero x on a sparse level
}

void MultigridHierarchy::cycle(int l) {
  Level& L = levels_[l];
  if (l + 1 == static_cast<int>(levels_.size())) {
    coarse_rhs_ = L.b.cast<double>();
    coarsest_.solveInPlace(coarse_rhs_);
    L.x = coarse_rhs_.cast<Real>();
    return;
  }
  Level& C = levels_[l + 1];
  smooth(L, true);
  // The finest level's transfers are matrix-free (grid_transfer.h) unless cubic.
  const bool transfer_free = L.matrix_free && !opt_.cubic;
  residual(L);
  if (transfer_free)
    restrict_to_coarse(L.dims, C.dims, L.r.data(), C.b.data());
  else
    spmv(L.R, L.r, C.b, Mode::Assign);
  cycle(l + 1);
  // Further corrections (W-cycle) solve the same coarse problem again, for what the first
  // left. With Galerkin operators the restricted residual after x += P e is
  // Pᵀ(r − A P e) = b_c − A_c e, so they run on the coarse level alone: one coarse product
  // instead of a residual, a restriction and a prolongation on this level (which cost
  // 8× more). Above the coarsest level the first correction is already exact.
  const int corrections = corrections_[l];
  if (corrections > 1) {
    C.b0.swap(C.b);  // the coarse right-hand side, kept
    C.e.swap(C.x);   // the corrections so far
    for (int g = 1; g < corrections; ++g) {
      sparse_residual(C.Af, C.e.data(), C.b0.data(), C.b.data());
      cycle(l + 1);
      add(C.x, C.e);
    }
    C.e.swap(C.x);
    C.b0.swap(C.b);
  }
  if (transfer_free)
    prolong_add(L.dims, C.dims, pinned_.data(), C.x.data(), L.x.data());
  else
    spmv(L.P, C.x, L.x, Mode::Add);
  smooth(L, false);
}

void MultigridHierarchy::apply(FieldF& r, FieldF& z, const double* dot_with, double dots[3]) {
  // The caller's vectors become the finest level's for the cycle (swaps, not 3n copies;
  // the cycle only reads b).
  Level& F = levels_[0];
  dot_with_ = dots ? dot_with : nullptr;
  dot_done_ = false;
  dot_partials_.assign(8 * static_cast<size_t>(std::max(1, omp_get_max_threads())), 0.0);
  F.b.swap(r);
  cycle(0);
  F.b.swap(r);
  z.swap(F.x);
  dot_with_ = nullptr;
  if (!dots) return;
  dots[0] = dots[1] = dots[2] = 0;
  if (dot_done_) {
    for (size_t t = 0; t < dot_partials_.size(); t += 8)
      for (int k = 0; k < 3; ++k) dots[k] += dot_partials_[t + k];
    return;
  }
  // A single-level hierarchy ends with the dense solve, not a smoothing step.
  const Real* zp = z.data();
  for (std::ptrdiff_t f = 0; f < z.size(); ++f) dots[f % 3] += dot_with[f] * static_cast<double>(zp[f]);
}

}  // namespace lapis::hair_field::detail
