#include "src/core/load_history.hpp"

#include <algorithm>
#include <cmath>

namespace mpsolid {

double LoadHistory::factor(double tau) const {
  switch (kind) {
    case Kind::step:
      return 1.0;
    case Kind::ramp:
      return tau >= rise_time ? 1.0 : tau / rise_time;
    case Kind::table: {
      if (tau <= times.front()) return factors.front();
      if (tau >= times.back()) return factors.back();
      const auto k = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), tau) -
                                              times.begin());
      const double s = (tau - times[k - 1]) / (times[k] - times[k - 1]);
      return factors[k - 1] + s * (factors[k] - factors[k - 1]);
    }
    case Kind::friedlander:
      return (1.0 - tau / duration) * std::exp(-decay * tau / duration);
  }
  return 1.0;
}

const char* history_kind(const LoadHistory& h) {
  switch (h.kind) {
    case LoadHistory::Kind::step:
      return "step";
    case LoadHistory::Kind::ramp:
      return "ramp";
    case LoadHistory::Kind::table:
      return "table";
    case LoadHistory::Kind::friedlander:
      return "friedlander";
  }
  return "step";
}

}  // namespace mpsolid
