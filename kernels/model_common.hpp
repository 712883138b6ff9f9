#pragma once
// What every bond model shares besides the bond loop: its options and the
// integrity check it reports to the blow-up diagnosis.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace mpsolid {

struct ModelOptions {
  double hourglass = 1.0;            // finite_strain: hourglass penalty coefficient alpha
  bool consistent_hourglass = true;  // finite_strain: full gradient (true) or F held fixed
  double min_jacobian = 0.1;  // finite_strain: J at or below this is a collapsed neighbourhood
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

}  // namespace mpsolid
