#pragma once
// A Python value as the TOML text of a --set value: bool -> true/false,
// int -> decimal, float -> repr (1e-05, 1e+20, inf, nan are TOML too),
// str -> a basic string with escapes, list/tuple -> [a, b], dict -> an
// inline table. Throws TypeError for anything else.
#include <string>

#include <pybind11/pybind11.h>

namespace mpsolid::python {

std::string toml_value_text(pybind11::handle value);

}  // namespace mpsolid::python
