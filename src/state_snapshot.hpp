#pragma once
// A copy of everything that evolves in time (particle state, rigid-body poses,
// load bookkeeping, the step), to go back to a known-good state.
#include <cstdint>
#include <vector>

#include "src/step.hpp"

namespace mpsolid {

struct StateSnapshot {
  std::int64_t step = -1;
  std::vector<double> x, y, vx, vy, theta, omega;
  std::vector<RigidBody> rigid_bodies;
  std::vector<StepLoad> loads;

  bool empty() const { return step < 0; }
  static StateSnapshot capture(const SolverState& s);
  void restore(SolverState& s) const;
};

inline StateSnapshot StateSnapshot::capture(const SolverState& s) {
  const ParticleStore& p = s.particles;
  return {s.step, p.x, p.y, p.vx, p.vy, p.theta, p.omega, s.rigid_bodies, s.loads};
}

inline void StateSnapshot::restore(SolverState& s) const {
  ParticleStore& p = s.particles;
  p.x = x;
  p.y = y;
  p.vx = vx;
  p.vy = vy;
  p.theta = theta;
  p.omega = omega;
  s.rigid_bodies = rigid_bodies;
  s.loads = loads;
  s.step = step;
}

}  // namespace mpsolid
