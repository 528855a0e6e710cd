// lapis.solver in Python: the CHOLMOD Cholesky and the updatable factor on scipy.sparse
// matrices, for users who want the kernel alone. Right-hand sides are (n,) or (n, k) float64;
// the factorizations and solves run without the GIL.
#include <pybind11/stl.h>

#include <string>

#include "arrays.h"
#include "bindings.h"
#include "lapis/solver/cholesky.h"
#include "lapis/solver/updatable_cholesky.h"

namespace lapis::python {
namespace {

using namespace lapis::solver;
using namespace pybind11::literals;

// B as the column-major matrix the solvers take; `vector` tells whether it was 1-D.
DenseMatrix rhs(const py::handle& B, bool& vector) {
  const py::array a =
      py::isinstance<py::array>(B) ? py::reinterpret_borrow<py::array>(B) : py::array_t<double>::ensure(B);
  vector = a.ndim() == 1;
  if (vector) return to_vector(a, "B");
  return to_dense(a, "B", -1);
}

py::array solution(DenseMatrix&& X, bool vector) {
  if (vector) return to_numpy(Eigen::VectorXd(X.col(0)));
  return to_numpy(std::move(X));
}

template <class Solver>
py::array solve_with(const Solver& s, const py::handle& B) {
  bool vector = false;
  const DenseMatrix b = rhs(B, vector);
  DenseMatrix X;
  {
    py::gil_scoped_release release;
    X = s.solve(b);
  }
  return solution(std::move(X), vector);
}

py::dict factor_report(const FactorReport& r) {
  return py::dict("backend"_a = to_string(r.backend), "kind"_a = to_string(r.kind), "n"_a = r.n, "nnz_A"_a = r.nnz_A,
                  "nnz_L"_a = r.nnz_L, "flops"_a = r.flops, "ordering"_a = r.ordering, "analyze_ms"_a = r.analyze_ms,
                  "factorize_ms"_a = r.factorize_ms, "solve_ms"_a = r.solve_ms);
}

py::dict modify_report(const ModifyReport& r) {
  return py::dict("method"_a = to_string(r.method), "rank"_a = r.rank, "predicted_updown_ms"_a = r.predicted_updown_ms,
                  "predicted_refactor_ms"_a = r.predicted_refactor_ms, "ms"_a = r.ms);
}

Backend backend(const std::string& name) {
  if (name == "cholmod") return Backend::Cholmod;
  if (name == "eigen") return Backend::Eigen;
  throw InvalidArgument("backend must be cholmod or eigen, not '" + name + "'");
}

ModifyMethod modify_method(const std::string& name) {
  for (ModifyMethod m : {ModifyMethod::Auto, ModifyMethod::UpdateDowndate, ModifyMethod::Refactorize})
    if (name == to_string(m)) return m;
  throw InvalidArgument("method must be " + std::string(to_string(ModifyMethod::Auto)) + ", " +
                        to_string(ModifyMethod::UpdateDowndate) + " or " + to_string(ModifyMethod::Refactorize) +
                        ", not '" + name + "'");
}

// update() or downdate(): C converted with the GIL held, the modification run without it, the
// report converted with it again.
auto modify(ModifyReport (UpdatableCholesky::*method)(const SparseMatrix&)) {
  return [method](UpdatableCholesky& f, const py::handle& C) {
    const SparseMatrix c = from_scipy(C, "C");
    ModifyReport r;
    {
      py::gil_scoped_release release;
      r = (f.*method)(c);
    }
    return modify_report(r);
  };
}

// Converts A with the GIL held, then runs fn(A) without it; fn returns nothing (a Python
// object must not be made without the GIL).
template <class Self, class Fn>
auto with_sparse(Fn fn) {
  return [fn](Self& self, const py::handle& A) {
    const SparseMatrix a = from_scipy(A, "A");
    py::gil_scoped_release release;
    return fn(self, a);
  };
}

void bind_cholesky(py::module_& m) {
  py::class_<Cholesky>(m, "Cholesky", R"(Sparse Cholesky factorization of a symmetric positive definite matrix
(CHOLMOD, supernodal by default): analyze once, factorize and refactorize with the same pattern,
solve many right-hand sides at once.

    chol = lapis.Cholesky()
    chol.compute(A)          # A: scipy.sparse, only its lower triangle is read
    X = chol.solve(B)        # B: (n,) or (n, k) float64

Raises NotPositiveDefinite (with .column) for a matrix that is not positive definite.)")
      .def(py::init([](const std::string& b, const std::string& kind, int threads) {
             CholeskyOptions o;
             o.backend = backend(b);
             if (kind != "supernodal" && kind != "simplicial")
               throw InvalidArgument("kind must be supernodal or simplicial, not '" + kind + "'");
             o.kind = kind == "supernodal" ? FactorKind::Supernodal : FactorKind::Simplicial;
             o.threads = threads;
             return new Cholesky(o);
           }),
           "backend"_a = "cholmod", "kind"_a = "supernodal", "threads"_a = 0)
      .def("analyze", with_sparse<Cholesky>([](Cholesky& c, const SparseMatrix& A) { c.analyze(A); }), "A"_a,
           "Symbolic analysis: chooses the fill-reducing ordering.")
      .def("factorize", with_sparse<Cholesky>([](Cholesky& c, const SparseMatrix& A) { c.factorize(A); }), "A"_a,
           "Numeric factorization (re-analyzes when the pattern changed).")
      .def("compute", with_sparse<Cholesky>([](Cholesky& c, const SparseMatrix& A) { c.compute(A); }), "A"_a,
           "analyze() + factorize().")
      .def("solve", &solve_with<Cholesky>, "B"_a, "X with A X = B; B (n,) or (n, k) float64, X of the same shape.")
      .def_property_readonly("factorized", &Cholesky::factorized, "Whether a factor is held (solve() works).")
      .def_property_readonly("rows", &Cholesky::rows, "n, the order of the factorized matrix.")
      .def(
          "report", [](const Cholesky& c) { return factor_report(c.report()); },
          "What the last analysis, factorization and solve cost and produced.");
  m.def(
      "solve_spd",
      [](const py::handle& A, const py::handle& B) {
        const SparseMatrix a = from_scipy(A, "A");
        bool vector = false;
        const DenseMatrix b = rhs(B, vector);
        DenseMatrix X;
        {
          py::gil_scoped_release release;
          X = solve_spd(a, b);
        }
        return solution(std::move(X), vector);
      },
      "A"_a, "B"_a, "Factorizes the SPD matrix A (scipy.sparse) and solves A X = B once.");
}

void bind_updatable(py::module_& m) {
  py::class_<UpdatableCholesky>(m, "UpdatableCholesky", R"(A Cholesky factor modified in place: A +- C C^T by
CHOLMOD's rank-k update/downdate, and changes of diagonal weights (A = A0 + diag(w)), each
choosing update/downdate or refactorization by a cost model; the report says which ran.

    f = lapis.UpdatableCholesky()
    f.compute(A0, w)                         # factorizes A0 + diag(w)
    f.set_diagonal_weights([3, 7], [0., 5.]) # one downdate and one update
    x = f.solve(b))")
      .def(py::init([](const std::string& b, const std::string& method, int threads) {
             UpdatableCholeskyOptions o;
             o.backend = backend(b);
             o.method = modify_method(method);
             o.threads = threads;
             return new UpdatableCholesky(o);
           }),
           "backend"_a = "cholmod", "method"_a = "auto", "threads"_a = 0)
      .def(
          "compute",
          [](UpdatableCholesky& f, const py::handle& A, const py::object& weights) {
            const SparseMatrix a = from_scipy(A, "A");
            if (weights.is_none()) {
              py::gil_scoped_release release;
              f.compute(a);
              return;
            }
            const Eigen::VectorXd w = to_vector(weights, "diagonal_weights");
            py::gil_scoped_release release;
            f.compute(a, w);
          },
          "A"_a, "diagonal_weights"_a = py::none(),
          "Factorizes A, or A + diag(diagonal_weights) remembering the weights (A must store its diagonal).")
      .def("update", modify(&UpdatableCholesky::update), "C"_a,
           "A += C C^T for C (n, r) scipy.sparse; returns the modification's report.")
      .def("downdate", modify(&UpdatableCholesky::downdate), "C"_a,
           "A -= C C^T; raises NotPositiveDefinite and keeps the previous A if A would become indefinite.")
      .def(
          "set_diagonal_weights",
          [](UpdatableCholesky& f, const py::handle& indices, const py::handle& weights) {
            const std::vector<int> i = to_indices(indices, "indices");
            const Eigen::VectorXd w = to_vector(weights, "weights");
            if (static_cast<Eigen::Index>(i.size()) != w.size())
              throw py::value_error("indices has " + std::to_string(i.size()) + " entries but weights has " +
                                    std::to_string(w.size()));
            ModifyReport r;
            {
              py::gil_scoped_release release;
              r = f.set_diagonal_weights(i, std::span<const double>(w.data(), static_cast<size_t>(w.size())));
            }
            return modify_report(r);
          },
          "indices"_a, "weights"_a,
          "Sets the diagonal weights of `indices` (increases: one update, decreases: one downdate).")
      .def("diagonal_weight", &UpdatableCholesky::diagonal_weight, "i"_a,
           "The weight currently added to A[i, i] through compute() and set_diagonal_weights().")
      .def("solve", &solve_with<UpdatableCholesky>, "B"_a, "X with A X = B for the current A.")
      .def(
          "matrix", [](const UpdatableCholesky& f) { return to_scipy(SparseMatrix(f.matrix())); },
          "The matrix the factor represents now (a scipy.sparse copy).")
      .def_property_readonly("rows", &UpdatableCholesky::rows, "n, the order of the factorized matrix.")
      .def(
          "report", [](const UpdatableCholesky& f) { return factor_report(f.report()); }, "The factorization's report.")
      .def(
          "last_report", [](const UpdatableCholesky& f) { return modify_report(f.last_report()); },
          "The last modification's report.")
      .def(
          "set_method", [](UpdatableCholesky& f, const std::string& m) { f.set_method(modify_method(m)); }, "method"_a,
          "Forces every later modification to one method ('auto', 'update/downdate', 'refactorize').");
}

}  // namespace

void bind_solver(py::module_& m) {
  bind_cholesky(m);
  bind_updatable(m);
}

}  // namespace lapis::python
