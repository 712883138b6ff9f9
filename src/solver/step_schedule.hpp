#pragma once
// How one step is spread over the threads of a team (src/core/parallel.hpp):
// which thread times a phase, and whether a rigid body can be projected by
// the thread that kicked its particles.
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

// True when every rigid body lies inside one static block of the moving
// particles, so its projection can follow its particles' kick on one thread.
inline bool bodies_in_single_blocks(const SolverState& s) {
  const Range moving = s.particles.moving();
  const std::size_t threads = team_size();
  for (const RigidBody& body : s.rigid_bodies) {
    bool inside = false;
    for (std::size_t r = 0; r < threads && !inside; ++r) {
      const Range block = static_block(moving.begin, moving.end, r, threads);
      inside = block.begin <= body.range.begin && body.range.end <= block.end;
    }
    if (!inside) return false;
  }
  return true;
}

}  // namespace mpsolid
