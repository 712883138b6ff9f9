#pragma once
// The pieces of the _mpsolid module, one binding per file; module.cpp puts
// them together.
#include <pybind11/pybind11.h>

namespace mpsolid::python {

void bind_case(pybind11::module_& m);        // case_binding.cpp
void bind_simulation(pybind11::module_& m);  // simulation_binding.cpp (needs Case)
void bind_run(pybind11::module_& m);         // run_binding.cpp (needs Case)

}  // namespace mpsolid::python
