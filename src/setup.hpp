#pragma once
// From a validated case to the initial solver state: lattice particles,
// storage grouped by kind, masses, the bond table, rigid bodies and loads.
#include <vector>

#include "src/case_spec.hpp"
#include "src/step.hpp"

namespace mpsolid {

struct SetupResult {
  SolverState state;
  std::vector<Range> body_ranges;  // storage range of each body (case order)
};

SetupResult set_up(const CaseSpec& spec, PhaseTimers& timers);

}  // namespace mpsolid
