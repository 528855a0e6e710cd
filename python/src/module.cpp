// The extension lapis._lapis: the array conversions every binding shares, the exception
// mapping, and the registration of each module's bindings. The package python/lapis wraps it.
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "arrays.h"
#include "bindings.h"
#include "lapis/core/error.h"

using namespace pybind11::literals;

namespace lapis::python {

std::string shape_text(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

namespace {

// An ndarray as it is; anything else (a list) converted with `dtype`.
template <class T>
py::array as_array(const py::handle& obj) {
  if (py::isinstance<py::array>(obj)) return py::reinterpret_borrow<py::array>(obj);
  return py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(obj);
}

std::string dtype_text(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

void require_shape(const py::array& a, const char* name, int ndim, py::ssize_t cols, const char* expected) {
  if (a.ndim() != ndim || (cols >= 0 && a.shape(ndim - 1) != cols))
    throw py::value_error(std::string(name) + " must have shape " + expected + ", not " + shape_text(a));
}

// Index arrays: int32 as they are, int64 when every value fits in int.
template <class Out>
void copy_indices(const py::array& a, const char* name, Out* out) {
  const py::ssize_t n = a.size();
  if (a.dtype().kind() == 'i' && a.itemsize() == 4) {
    auto c = py::array_t<std::int32_t, py::array::c_style>::ensure(a);
    for (py::ssize_t i = 0; i < n; ++i) out[i] = c.data()[i];
    return;
  }
  if (a.dtype().kind() == 'i' && a.itemsize() == 8) {
    auto c = py::array_t<std::int64_t, py::array::c_style>::ensure(a);
    for (py::ssize_t i = 0; i < n; ++i) {
      const std::int64_t v = c.data()[i];
      if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
        throw py::value_error(std::string(name) + "[" + std::to_string(i) + "] = " + std::to_string(v) +
                              " does not fit in a 32-bit index");
      out[i] = static_cast<int>(v);
    }
    return;
  }
  throw py::type_error(std::string(name) + " must be int32 or int64, not " + dtype_text(a));
}

}  // namespace

Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> to_dense(const py::handle& obj, const char* name,
                                                                                int cols) {
  const py::array a = as_array<double>(obj);
  if (a.dtype().kind() != 'f' || a.itemsize() != 8)
    throw py::type_error(std::string(name) + " must be float64, not " + dtype_text(a));
  const std::string expected = cols < 0 ? "(n, k)" : "(n, " + std::to_string(cols) + ")";
  require_shape(a, name, 2, cols, expected.c_str());
  auto c = py::array_t<double, py::array::c_style>::ensure(a);  // a copy only when strided
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> out(c.shape(0), c.shape(1));
  std::copy(c.data(), c.data() + c.size(), out.data());
  return out;
}

geometry::Vertices to_vertices(const py::handle& obj, const char* name) { return to_dense(obj, name, 3); }

namespace {

// An (n, Cols) int32 or int64 array as row-major ints.
template <int Cols>
Eigen::Matrix<int, Eigen::Dynamic, Cols, Eigen::RowMajor> to_index_rows(const py::handle& obj, const char* name) {
  const py::array a = as_array<std::int64_t>(obj);
  const std::string expected = "(n, " + std::to_string(Cols) + ")";
  require_shape(a, name, 2, Cols, expected.c_str());
  Eigen::Matrix<int, Eigen::Dynamic, Cols, Eigen::RowMajor> out(a.shape(0), Cols);
  copy_indices(a, name, out.data());
  return out;
}

}  // namespace

geometry::Faces to_faces(const py::handle& obj, const char* name) { return to_index_rows<3>(obj, name); }

geometry::Tets to_tets(const py::handle& obj, const char* name) { return to_index_rows<4>(obj, name); }

std::vector<int> to_indices(const py::handle& obj, const char* name) {
  const py::array a = as_array<std::int64_t>(obj);
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must have shape (n,), not " + shape_text(a));
  std::vector<int> out(static_cast<size_t>(a.size()));
  if (!out.empty()) copy_indices(a, name, out.data());
  return out;
}

Eigen::VectorXd to_vector(const py::handle& obj, const char* name) {
  const py::array a = as_array<double>(obj);
  if (a.dtype().kind() != 'f' || a.itemsize() != 8)
    throw py::type_error(std::string(name) + " must be float64, not " + dtype_text(a));
  if (a.ndim() != 1) throw py::value_error(std::string(name) + " must have shape (n,), not " + shape_text(a));
  auto c = py::array_t<double, py::array::c_style>::ensure(a);
  return Eigen::Map<const Eigen::VectorXd>(c.data(), c.size());
}

py::object to_scipy(Sparse&& A) {
  py::module_ scipy_sparse;
  try {
    scipy_sparse = py::module_::import("scipy.sparse");
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_ImportError)) throw;
    throw py::import_error(
        "lapis: sparse matrices are returned as scipy.sparse matrices; install SciPy "
        "(Debian: python3-scipy)");
  }
  A.makeCompressed();
  auto* owned = new Sparse(std::move(A));
  py::capsule owner(owned, [](void* p) { delete static_cast<Sparse*>(p); });
  const auto nnz = static_cast<py::ssize_t>(owned->nonZeros());
  py::array data = py::array_t<double>({nnz}, {py::ssize_t{8}}, owned->valuePtr(), owner);
  py::array indices = py::array_t<int>({nnz}, {py::ssize_t{4}}, owned->innerIndexPtr(), owner);
  py::array indptr = py::array_t<int>({static_cast<py::ssize_t>(owned->outerSize() + 1)}, {py::ssize_t{4}},
                                      owned->outerIndexPtr(), owner);
  // copy=False keeps the views (scipy would otherwise copy int32 index arrays it can use as they are).
  return scipy_sparse.attr("csc_matrix")(py::make_tuple(data, indices, indptr),
                                         "shape"_a = py::make_tuple(owned->rows(), owned->cols()), "copy"_a = false);
}

Sparse from_scipy(const py::handle& matrix, const char* name) {
  const std::string n = name;
  if (!py::hasattr(matrix, "tocsc")) throw py::type_error(n + " must be a scipy.sparse matrix");
  const py::object A = matrix.attr("tocsc")();
  const auto shape = A.attr("shape").cast<std::pair<py::ssize_t, py::ssize_t>>();
  const py::ssize_t rows = shape.first, cols = shape.second;
  const Eigen::VectorXd values = to_vector(A.attr("data"), (n + ".data").c_str());
  const std::vector<int> inner = to_indices(A.attr("indices"), (n + ".indices").c_str());
  const std::vector<int> outer = to_indices(A.attr("indptr"), (n + ".indptr").c_str());
  if (static_cast<py::ssize_t>(outer.size()) != cols + 1 || inner.size() != static_cast<size_t>(values.size()) ||
      outer.front() != 0 || outer.back() != static_cast<int>(inner.size()))
    throw py::value_error(n + ": inconsistent CSC arrays (indptr, indices, data)");
  Sparse out(rows, cols);
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(inner.size());
  for (py::ssize_t j = 0; j < cols; ++j) {
    if (outer[j] > outer[j + 1]) throw py::value_error(n + ": indptr is not non-decreasing");
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (inner[k] < 0 || inner[k] >= rows)
        throw py::value_error(n + ".indices[" + std::to_string(k) + "] = " + std::to_string(inner[k]) +
                              " is outside [0, " + std::to_string(rows) + ")");
      t.emplace_back(inner[k], static_cast<int>(j), values[k]);
    }
  }
  out.setFromTriplets(t.begin(), t.end());  // sums duplicates, as scipy does
  return out;
}

geometry::TriMesh to_mesh(const py::handle& V, const py::handle& F) { return {to_vertices(V, "V"), to_faces(F, "F")}; }

namespace {

// lapis.Error and its subclasses, each also deriving from the built-in a Python user would
// catch (InvalidArgument is a ValueError, IoError an OSError, ...), so `except ValueError`
// works as in any other library. Most derived first: the translator tries them in order.
struct Exceptions {
  py::object error, invalid_argument, usage_error, io_error, not_positive_definite, solver_failure, resource_limit;
};

py::object new_exception(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("lapis.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!type) throw py::error_already_set();
  py::object cls = py::reinterpret_steal<py::object>(type);
  m.attr(name) = cls;
  return cls;
}

void raise(const py::object& cls, const char* what) { PyErr_SetString(cls.ptr(), what); }

void bind_errors(py::module_& m) {
  static Exceptions e;  // lives as long as the interpreter keeps the module
  auto builtin = [](const char* name) { return py::module_::import("builtins").attr(name); };
  e.error = new_exception(m, "Error", py::make_tuple(builtin("Exception")), "Base of every error Lapis raises.");
  e.invalid_argument = new_exception(m, "InvalidArgument", py::make_tuple(e.error, builtin("ValueError")),
                                     "An argument is out of its domain: sizes, indices, NaN, empty input.");
  e.usage_error = new_exception(m, "UsageError", py::make_tuple(e.invalid_argument), "A malformed command line.");
  e.io_error = new_exception(m, "IoError", py::make_tuple(e.error, builtin("OSError")),
                             "A file could not be read or written, or its content is malformed.");
  e.not_positive_definite =
      new_exception(m, "NotPositiveDefinite", py::make_tuple(e.error, builtin("ArithmeticError")),
                    "A matrix that must be symmetric positive definite is not; .column is where it broke.");
  e.solver_failure = new_exception(m, "SolverFailure", py::make_tuple(e.error, builtin("RuntimeError")),
                                   "The sparse solver backend failed (out of memory, internal error).");
  e.resource_limit = new_exception(m, "ResourceLimit", py::make_tuple(e.error, builtin("MemoryError")),
                                   "A request would need more memory than allowed.");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const NotPositiveDefinite& x) {
      py::object value = e.not_positive_definite(x.what());
      value.attr("column") = x.column();
      PyErr_SetObject(e.not_positive_definite.ptr(), value.ptr());
    } catch (const UsageError& x) {
      raise(e.usage_error, x.what());
    } catch (const InvalidArgument& x) {
      raise(e.invalid_argument, x.what());
    } catch (const IoError& x) {
      raise(e.io_error, x.what());
    } catch (const SolverFailure& x) {
      raise(e.solver_failure, x.what());
    } catch (const ResourceLimit& x) {
      raise(e.resource_limit, x.what());
    } catch (const Error& x) {
      raise(e.error, x.what());
    }
  });
}

}  // namespace
}  // namespace lapis::python

PYBIND11_MODULE(_lapis, m) {
  m.doc() = "The C++ core of the lapis package; use `import lapis`, which wraps it.";
  lapis::python::bind_errors(m);
  lapis::python::bind_geometry(m);
  lapis::python::bind_deform(m);
  lapis::python::bind_solver(m);
  lapis::python::bind_merge(m);
  lapis::python::bind_hair(m);
  lapis::python::bind_hair_live(m);
}
