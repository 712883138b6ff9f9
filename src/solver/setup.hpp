#pragma once
// From a validated case to the initial solver state: lattice particles,
// storage grouped by kind, masses, the bond table, rigid bodies and loads.
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/solver/step.hpp"

namespace mpsolid {

struct SetupResult {
  SolverState state;
  std::vector<Range> body_ranges;   // storage range of each body (case order)
  std::vector<std::size_t> probes;  // storage index of each probe's particle (case order)
};

// Particles, bonds, rigid bodies, holds, probes and loads; the loads' first
// steps and the state's dt are set by schedule_loads once dt is known
// (after the estimate when dt is "auto").
SetupResult set_up(const CaseSpec& spec, PhaseTimers& timers);

// Sets the state's dt and each load's first step k (k dt >= start).
void schedule_loads(SolverState& s, const CaseSpec& spec);

}  // namespace mpsolid
