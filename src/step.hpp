#pragma once
// One time step, in order (MODEL.md section 2). Holds no physics itself:
// half angles -> strain pass -> force/torque pass -> loads -> holds ->
// integrate -> rigid-body projection.
#include <cstdint>
#include <vector>

#include "kernels/half_angles.hpp"
#include "src/bonds.hpp"
#include "src/holds.hpp"
#include "src/integrator.hpp"
#include "src/loads.hpp"
#include "src/particle_store.hpp"
#include "src/rigid_body.hpp"
#include "src/timers.hpp"

namespace mpsolid {

struct SolverState {
  ParticleStore particles;
  BondTable bonds;
  std::vector<RigidBody> rigid_bodies;
  std::vector<StepLoad> loads;
  std::vector<HeldRange> holds;
  double dt = 0;
  std::int64_t step = 0;
  // The largest external work seen by a stability check: the energy scale of
  // the balance check, which must not shrink when a load gets work back.
  double peak_work = 0;
};

// Fields that depend on the current positions only: half angles, strain and
// pressure. Walls keep theta = 0, so their half angles are set once.
template <class Model>
void update_strain(Model& model, SolverState& s, PhaseTimers& timers) {
  if constexpr (Model::uses_rotation) {
    auto t = timers.time(Phase::half_angles);
    compute_half_angles(s.particles, s.particles.moving());
  }
  auto t = timers.time(Phase::strain);
  model.compute_strain(s.particles, s.bonds, s.particles.all());
}

template <class Model>
void advance_one_step(Model& model, SolverState& s, PhaseTimers& timers) {
  ParticleStore& p = s.particles;
  constexpr bool rot = Model::uses_rotation;
  update_strain(model, s, timers);
  {
    auto t = timers.time(Phase::forces);
    model.compute_forces(p, s.bonds, p.moving());
  }
  if (!s.loads.empty()) {
    auto t = timers.time(Phase::loads);
    apply_loads(p, s.loads, s.step);
  }
  if (!s.holds.empty()) clear_held_forces(p, s.holds, p.moving());
  {
    auto t = timers.time(Phase::integrate);
    kick_drift(p, p.elastic, s.dt, rot);
    kick(p, p.rigid, s.dt, rot);
  }
  if (!s.rigid_bodies.empty()) {
    auto t = timers.time(Phase::rigid_bodies);
    for (RigidBody& body : s.rigid_bodies) project_rigid_body(p, body, s.dt, rot);
  }
  ++s.step;
}

}  // namespace mpsolid
