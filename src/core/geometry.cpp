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

std::vector<Site> fill_rectangle(const double x[2], const double y[2], double l0) {
  const LatticeSpan sx = lattice_span(x[0], x[1], l0);
  const LatticeSpan sy = lattice_span(y[0], y[1], l0);
  std::vector<Site> sites;
  sites.reserve(static_cast<std::size_t>(sx.count() * sy.count()));
  for (std::int64_t m = sy.first; m <= sy.last; ++m)
    for (std::int64_t k = sx.first; k <= sx.last; ++k)
      sites.push_back({lattice_coordinate(k, l0), lattice_coordinate(m, l0)});
  return sites;
}

}  // namespace mpsolid
