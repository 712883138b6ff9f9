#pragma once
// Fixing a case's time step: as given, or for time.dt = "auto" safety x the
// model's stable-step limit (src/solver/stable_step.hpp, contact's bound
// added), estimated about the set-up state where the run steps it (on this
// process, or on every rank's part with the same bits) and rounded so that
// every output interval is a whole number of steps
// (CaseSpec::set_auto_time_step). Set-up reads no dt; only the loads' first
// steps wait for it (schedule_loads).
#include <string>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stable_step_estimate.hpp"
#include "src/distributed/rank_group.hpp"

namespace mpsolid {

struct RankPart;

// Whether the case's step is still to be chosen from the estimate.
inline bool needs_time_step(const CaseSpec& spec) {
  return spec.dt_auto && !(spec.dt > 0);
}

// The model's stable-step limit about the state `s` on this process; zeros
// when there is no elastic particle.
StableStepEstimate estimate_case_stable_step(const CaseSpec& spec, const SolverState& s);
// The same about the whole state that the ranks' parts make up: every rank
// of `world` calls it with its part and gets the one-process estimate's
// bits. The part's halo cost is left as it was (the estimate is set-up).
StableStepEstimate estimate_part_stable_step(const CaseSpec& spec, RankPart& part,
                                             const RankGroup& world);

// Sets time.dt = "auto"'s step from the estimate; throws InputError when
// there is none (no elastic particle to estimate from).
void choose_time_step(CaseSpec& spec, const StableStepEstimate& estimate);

// For a given time.dt above the estimate's limit, a warning naming both and
// time.dt = "auto"; "" otherwise.
std::string fixed_time_step_warning(const CaseSpec& spec, const StableStepEstimate& estimate);

}  // namespace mpsolid
