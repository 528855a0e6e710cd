// What the deformation bindings share across their translation units.
#pragma once

#include <pybind11/pybind11.h>

#include "lapis/mesh_deform/deformer.h"

namespace lapis::python {

// A Selection from Python: roi indices, a sequence of region index arrays, point indices.
mesh_deform::Selection to_selection(const pybind11::handle& roi, const pybind11::handle& regions,
                                    const pybind11::handle& points);

// Members of lapis._Deformer that only some methods have (salient features and subspace,
// isolines fields), and lapis._DeformationTransfer.
void bind_method_members(pybind11::class_<mesh_deform::Deformer>& deformer);
void bind_transfer(pybind11::module_& m);

}  // namespace lapis::python
