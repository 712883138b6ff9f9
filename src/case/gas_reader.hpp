#pragma once
// The [gas] section (docs/gas.md): the grid, the gas, its edges, its
// initial state by regions with an optional planar shock, the bodies it is
// coupled to, and its probes. Every problem is an InputError naming the
// file, the key and what is allowed.
#include "src/case/case_spec.hpp"
#include "src/case/table_reader.hpp"

namespace mpsolid {

// Reads [gas] into c.gas (after the bodies are read); nothing when absent.
void read_gas(TableReader& top, CaseSpec& c);

// The thinnest part of a shape: the shortest chord from the midpoint of an
// outline edge (holes' included) inward along its normal to the outline.
double thinnest_width(const Shape& shape);

}  // namespace mpsolid
