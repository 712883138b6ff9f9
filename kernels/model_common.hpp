#pragma once
// What every bond model shares besides the bond loop: the lattice constants
// its coefficients start from, and the integrity check it reports to the
// blow-up diagnosis.
#include <fmt/format.h>

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "kernels/bond_math.hpp"
#include "src/core/bonds.hpp"

namespace mpsolid {

// n0 of the bond table's lattice (MODEL.md section 1): square or cubic.
inline double number_density(const BondTable& bonds) {
  const BondGeometry& g = bonds.geometry;
  return g.dimension == 3 ? bond_math::lattice_number_density_3d(g.l0, g.re)
                          : bond_math::lattice_number_density(g.l0, g.re);
}

// Thresholds of the integrity checks, from the case's [stability] section.
struct IntegrityLimits {
  double min_jacobian = 0.1;  // J at or below this is a collapsed neighbourhood
};

// The worst particle by a model's own integrity measure (smallest is worst).
struct IntegrityReport {
  std::size_t particle = 0;
  std::size_t neighbor = 0;  // the bond's other end, where the measure is per bond
  double value = std::numeric_limits<double>::infinity();
  bool failed = false;
  std::string criterion;  // what failed, in words
};

// Index of the smallest value (first on ties): a deterministic serial scan.
inline std::size_t index_of_min(const std::vector<double>& values) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < values.size(); ++i)
    if (values[i] < values[best]) best = i;
  return best;
}
// The same among the indices of a non-empty `range`.
inline std::size_t index_of_min(const std::vector<double>& values, Range range) {
  std::size_t best = range.begin;
  for (std::size_t i = range.begin + 1; i < range.end; ++i)
    if (values[i] < values[best]) best = i;
  return best;
}

// Young's modulus of the Lame constants (the hourglass terms' E_i).
inline double youngs_modulus(double lambda, double mu) {
  return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
}

// The corrected-gradient models' check: the smallest J_i among the
// particles of a range, failed at or below the limit (a collapsed
// neighbourhood).
inline IntegrityReport jacobian_integrity(const std::vector<double>& jacobian,
                                          const IntegrityLimits& limits, Range range) {
  IntegrityReport r;
  if (range.empty()) return r;
  r.particle = index_of_min(jacobian, range);
  r.neighbor = r.particle;
  r.value = jacobian[r.particle];
  r.failed = !(r.value > limits.min_jacobian);
  r.criterion =
      fmt::format("particle neighbourhood collapsed (J = det F <= {})", limits.min_jacobian);
  return r;
}

}  // namespace mpsolid
