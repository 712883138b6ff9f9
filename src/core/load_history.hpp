#pragma once
// A load's time history: the factor its value (force, acceleration) is
// multiplied by, as a function of the time since the load's start.
//   step: 1;
//   ramp: tau / rise_time up to 1, then 1;
//   table: linear between (time, factor) points (times from the start,
//     increasing), the first factor before the first time, the last after
//     the last;
//   friedlander: the blast wave (1 - tau / t_d) exp(-b tau / t_d), with its
//     negative phase after t_d (scale the load's value by the peak
//     overpressure p_s).
#include <vector>

namespace mpsolid {

struct LoadHistory {
  enum class Kind { step, ramp, table, friedlander };
  Kind kind = Kind::step;
  double rise_time = 0;                // ramp (s)
  std::vector<double> times, factors;  // table (s from the start; factors)
  double duration = 0, decay = 0;      // friedlander: t_d (s) and b
  // The factor at tau >= 0 seconds after the start.
  double factor(double tau) const;
  // A step never changes after it switches on: its work telescopes.
  bool constant() const { return kind == Kind::step; }
  bool operator==(const LoadHistory&) const = default;
};

const char* history_kind(const LoadHistory& h);

}  // namespace mpsolid
