#include "strands.h"

#include <string>
#include <utility>

namespace lapis::python {

using hair_sketch::Strands;

Strands StrandPool::take() {
  if (free_.empty()) return {};
  Strands s = std::move(free_.back());
  free_.pop_back();
  return s;
}

void StrandPool::give_back(Strands strands) {
  if (free_.size() < kKept) free_.push_back(std::move(strands));
}

py::tuple strands_to_numpy(Strands&& strands, std::shared_ptr<StrandPool> pool) {
  // Eigen::Vector3f is three packed floats, so the points vector is an (n, 3) array as it is.
  static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float));
  struct Owner {
    Strands strands;
    std::shared_ptr<StrandPool> pool;
  };
  auto* owner = new Owner{std::move(strands), std::move(pool)};
  py::capsule base(owner, [](void* p) {
    auto* o = static_cast<Owner*>(p);
    if (o->pool) o->pool->give_back(std::move(o->strands));
    delete o;
  });
  const Strands& s = owner->strands;
  const auto n = static_cast<py::ssize_t>(s.points.size());
  const py::ssize_t f = sizeof(float);
  // An empty vector may have no storage; NumPy then allocates the (0, 3) array itself.
  py::array points = py::array_t<float>({n, py::ssize_t{3}}, {3 * f, f}, n ? s.points.front().data() : nullptr, base);
  py::array offsets = py::array_t<int>({static_cast<py::ssize_t>(s.offsets.size())},
                                       {static_cast<py::ssize_t>(sizeof(int))}, s.offsets.data(), base);
  return py::make_tuple(points, offsets);
}

Strands strands_from_numpy(const py::handle& points, const py::handle& offsets) {
  const py::array a = py::isinstance<py::array>(points) ? py::reinterpret_borrow<py::array>(points)
                                                        : py::array_t<float>::ensure(points);
  if (a.dtype().kind() != 'f' || a.itemsize() != 4)
    throw py::type_error("points must be float32, not " + py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 2 || a.shape(1) != 3) throw py::value_error("points must have shape (n, 3), not " + shape_text(a));
  const auto c = py::array_t<float, py::array::c_style>::ensure(a);
  Strands s;
  s.offsets = to_indices(offsets, "offsets");
  if (s.offsets.empty() || s.offsets.front() != 0 || s.offsets.back() != c.shape(0))
    throw py::value_error("offsets must run from 0 to the " + std::to_string(c.shape(0)) + " points");
  for (size_t i = 1; i < s.offsets.size(); ++i)
    if (s.offsets[i] < s.offsets[i - 1]) throw py::value_error("offsets must not decrease");
  s.points.resize(static_cast<size_t>(c.shape(0)));
  for (py::ssize_t i = 0; i < c.shape(0); ++i) s.points[static_cast<size_t>(i)] = {c.at(i, 0), c.at(i, 1), c.at(i, 2)};
  return s;
}

}  // namespace lapis::python
