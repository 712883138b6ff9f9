#pragma once
// Which thread of a team times a step's phases (src/core/parallel.hpp).
#include <optional>

#include "src/core/parallel.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"

namespace mpsolid {

// Times a phase on the team's rank 0 only (the timers are not shared); the
// time includes the wait at the phase's closing barrier.
class TeamPhase {
 public:
  TeamPhase(PhaseTimers& timers, Phase phase) {
    if (team_rank() == 0) scope_.emplace(timers, phase);
  }

 private:
  std::optional<PhaseTimers::Scope> scope_;
};

}  // namespace mpsolid
