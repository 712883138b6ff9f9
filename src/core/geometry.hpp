#pragma once
// The one global square lattice that bodies fill (src/core/region.hpp):
// site centres at ((k + 0.5) l0, (m + 0.5) l0). All bodies share the lattice,
// so bonds across bodies have the same spacing as inside them, and one
// `l0` override refines the whole case.
#include <cstdint>
#include <vector>

namespace mpsolid {

// Lattice indices k with centre (k + 0.5) l0 in [lo, hi): the half-open rule
// gives a site on a shared edge to exactly one body.
struct LatticeSpan {
  std::int64_t first = 0;
  std::int64_t last = -1;  // inclusive
  std::int64_t count() const { return last >= first ? last - first + 1 : 0; }
};
LatticeSpan lattice_span(double lo, double hi, double l0);

inline double lattice_coordinate(std::int64_t k, double l0) {
  return (static_cast<double>(k) + 0.5) * l0;
}

}  // namespace mpsolid
