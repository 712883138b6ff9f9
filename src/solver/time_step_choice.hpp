#pragma once
// Fixing a case's time step before anything that depends on it is built: as
// given, or for time.dt = "auto" safety x the model's stable-step limit,
// estimated on the case's initial state (src/solver/stable_step.hpp) and
// rounded so that every output interval is a whole number of steps
// (CaseSpec::set_auto_time_step). Set-up reads no dt, so the state set up for
// the estimate is the run's: it is handed on, not built twice.
#include <optional>
#include <string>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"
#include "src/solver/stable_step.hpp"

namespace mpsolid {

struct TimeStepChoice {
  CaseSpec spec;                       // dt > 0, in resolved_toml too
  StableStepEstimate estimate;         // zeros when dt was given
  std::optional<SolverState> initial;  // set up for the estimate (loads not yet scheduled)
};

// Throws InputError when "auto" has no elastic particle to estimate from.
TimeStepChoice fix_time_step(const CaseSpec& spec, PhaseTimers& timers);

// The model's stable-step limit on the state `initial` (contact's bound
// added), zeros when there is no elastic particle.
StableStepEstimate estimate_case_stable_step(const CaseSpec& spec, const SolverState& initial);

// For a given time.dt above that limit, a warning naming both and
// time.dt = "auto"; "" otherwise (and for "auto").
std::string fixed_time_step_warning(const CaseSpec& spec, const SolverState& initial);

}  // namespace mpsolid
