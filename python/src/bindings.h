// One registration function per bound module, each in its own translation unit.
#pragma once

#include <pybind11/pybind11.h>

namespace lapis::python {

void bind_geometry(pybind11::module_& m);
void bind_deform(pybind11::module_& m);
void bind_solver(pybind11::module_& m);
void bind_merge(pybind11::module_& m);
void bind_hair(pybind11::module_& m);
void bind_hair_live(pybind11::module_& m);  // after bind_hair: it takes a HairSession

}  // namespace lapis::python
