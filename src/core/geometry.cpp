#include "src/core/geometry.hpp"

#include <cmath>

namespace mpsolid {

LatticeSpan lattice_span(double lo, double hi, double l0) {
  // A relative slack of 1e-9 lattice units absorbs decimal round-off in the
  // case file (0.1 / 0.002 is not exactly 50 in binary).
  constexpr double kSlack = 1e-9;
  LatticeSpan span;
  span.first = static_cast<std::int64_t>(std::ceil(lo / l0 - 0.5 - kSlack));
  span.last = static_cast<std::int64_t>(std::ceil(hi / l0 - 0.5 - kSlack)) - 1;
  return span;
}

}  // namespace mpsolid
