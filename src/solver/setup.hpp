#pragma once
// From a validated case to the initial solver state: lattice particles,
// storage grouped by kind, masses, the bond table, rigid bodies and loads.
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"

namespace mpsolid {

// Particles, bonds, rigid bodies, holds, probes and loads; the loads' first
// steps are set by schedule_loads from the case's fixed dt.
SolverState set_up(const CaseSpec& spec, PhaseTimers& timers);

// Each load's first step k (k dt >= start); spec.dt must be fixed.
void schedule_loads(SolverState& s, const CaseSpec& spec);

}  // namespace mpsolid
