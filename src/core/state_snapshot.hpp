#pragma once
// A copy of everything that evolves in time (particle state, rigid-body poses,
// load bookkeeping, the step), to go back to a known-good state.
#include <cstdint>
#include <vector>

#include "src/core/solver_state.hpp"

namespace mpsolid {

struct StateSnapshot {
  std::int64_t step = -1;
  double peak_work = 0;
  std::vector<std::vector<double>> arrays;  // state_arrays(dimension), in that order
  std::vector<RigidBody> rigid_bodies;
  std::vector<StepLoad> loads;

  static StateSnapshot capture(const SolverState& s);
  void restore(SolverState& s) const;
};

inline StateSnapshot StateSnapshot::capture(const SolverState& s) {
  StateSnapshot snap{s.step, s.peak_work, {}, s.rigid_bodies, s.loads};
  for (const StateArray& a : state_arrays(s.particles.dimension))
    snap.arrays.push_back(s.particles.*a.member);
  return snap;
}

inline void StateSnapshot::restore(SolverState& s) const {
  std::size_t k = 0;
  for (const StateArray& a : state_arrays(s.particles.dimension))
    s.particles.*a.member = arrays[k++];
  s.rigid_bodies = rigid_bodies;
  s.loads = loads;
  s.step = step;
  s.peak_work = peak_work;
}

}  // namespace mpsolid
