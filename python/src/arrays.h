// NumPy arrays to and from the Eigen types of the C++ API. Inputs are checked (dtype, shape,
// index range of int64) with messages naming the argument, then copied into the C++ types,
// which own their storage (TriMesh is passed by value). Outputs are moved into a heap object
// that the returned array keeps alive: no copy.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "lapis/geometry/tet_mesh.h"
#include "lapis/geometry/tri_mesh.h"

namespace lapis::python {

namespace py = pybind11;

// "(4, 3)", "(7,)": how NumPy prints a shape, for messages.
std::string shape_text(const py::array& a);

// A float64 array of shape (n, cols) (cols < 0: any) as row-major doubles. Throws TypeError for
// another dtype, ValueError for another shape; a nested list is converted.
Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> to_dense(const py::handle& obj, const char* name,
                                                                                int cols);
// An (n, 3) float64 array.
geometry::Vertices to_vertices(const py::handle& obj, const char* name);
// An (n, 3) int32 or int64 array; int64 values must fit in int.
geometry::Faces to_faces(const py::handle& obj, const char* name);
// An (n, 4) int32 or int64 array of tetrahedra.
geometry::Tets to_tets(const py::handle& obj, const char* name);
// A 1-D int32 or int64 array (or a sequence of ints) as indices.
std::vector<int> to_indices(const py::handle& obj, const char* name);
// A 1-D float64 array.
Eigen::VectorXd to_vector(const py::handle& obj, const char* name);
geometry::TriMesh to_mesh(const py::handle& V, const py::handle& F);

// Moves m into an array that owns it.
template <class Matrix>
py::array to_numpy(Matrix&& m) {
  using M = std::decay_t<Matrix>;
  using Scalar = typename M::Scalar;
  auto* owned = new M(std::forward<Matrix>(m));
  py::capsule owner(owned, [](void* p) { delete static_cast<M*>(p); });
  const auto s = static_cast<py::ssize_t>(sizeof(Scalar));
  if constexpr (M::ColsAtCompileTime == 1) {
    return py::array_t<Scalar>({static_cast<py::ssize_t>(owned->size())}, {s}, owned->data(), owner);
  } else {
    const py::ssize_t rows = owned->rows(), cols = owned->cols();
    const std::vector<py::ssize_t> strides =
        M::IsRowMajor ? std::vector<py::ssize_t>{cols * s, s} : std::vector<py::ssize_t>{s, rows * s};
    return py::array_t<Scalar>({rows, cols}, strides, owned->data(), owner);
  }
}

template <class T>
py::array to_numpy(std::vector<T>&& v) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(owned->size())}, {static_cast<py::ssize_t>(sizeof(T))}, owned->data(),
                        owner);
}

using Sparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
// A scipy.sparse.csc_matrix whose three arrays view the moved matrix. Raises ImportError naming
// the Debian package when SciPy is missing. Call with the GIL held.
py::object to_scipy(Sparse&& A);
// Any scipy.sparse matrix (or anything with .tocsc()) with float64 values, copied.
Sparse from_scipy(const py::handle& A, const char* name);

}  // namespace lapis::python
