#pragma once
// The time step, in order (MODEL.md section 2). Holds no physics itself:
// strain pass -> (loads switch on) force/torque pass -> loads, holds,
// integrate, half angles -> rigid-body projection.
//
// A batch of steps runs in one parallel region (run_in_team): each phase is
// a loop over static per-thread particle blocks that ends with a barrier, and
// the serial bookkeeping (a load switching on, a rigid body's pose) is done
// by one thread. A thread's block of the moving particles is the same in the
// force pass and the integration, so loads, kick, drift and the new half
// angles of a particle need no barrier between them; a rigid body whose
// particles all lie in one block is projected by that block's thread right
// after its kick (one barrier less per step). Every particle's arithmetic is
// the same at any thread count and batch size: the same bits.
#include <algorithm>
#include <cstdint>

#include "src/core/half_angles.hpp"
#include "src/core/integrator.hpp"
#include "src/core/solver_state.hpp"
#include "src/solver/step_schedule.hpp"

namespace mpsolid {

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

// Loads, holds, kick, drift and half angles of the moving particles in one block,
// and the projection of the rigid bodies inside it when `project_bodies`.
template <bool Rotation>
void integrate_block(SolverState& s, double dt, Range block, bool project_bodies) {
  ParticleStore& p = s.particles;
  apply_loads(p, s.loads, block);
  if (!s.holds.empty()) clear_held_forces(p, s.holds, block);
  kick_drift(p, {block.begin, std::min(block.end, p.elastic.end)}, dt, Rotation);
  kick(p, {std::max(block.begin, p.rigid.begin), block.end}, dt, Rotation);
  if (!project_bodies) return;
  for (RigidBody& body : s.rigid_bodies)
    if (block.begin <= body.range.begin && body.range.end <= block.end)
      project_rigid_body(p, body, dt, Rotation);
}

// One step, called by every thread of the team. Needs the half angles of
// the current rotations (the previous step's integration leaves them).
template <class Model>
void team_step(Model& model, SolverState& s, double dt, PhaseTimers& timers, std::int64_t step,
               bool fused_bodies) {
  ParticleStore& p = s.particles;
  constexpr bool rot = Model::uses_rotation;
  {
    TeamPhase t(timers, Phase::strain);
    // Positions stay put until the force pass, and the switch-on is read
    // only after the strain pass's closing barrier.
    if (team_rank() == 0 && !s.loads.empty())
      serial_section([&] { activate_loads(p, s.loads, step); });
    model.compute_strain(p, s.bonds, p.all());
  }
  if constexpr (Model::forces_read_positions) {
    {
      TeamPhase t(timers, Phase::forces);
      model.compute_forces(p, s.bonds, p.moving());
    }
    TeamPhase t(timers, Phase::integrate);
    parallel_blocks(p.moving().begin, p.moving().end, [&](std::size_t b, std::size_t e) {
      integrate_block<rot>(s, dt, {b, e}, fused_bodies);
    });
  } else {
    // A block's forces read no position, so its integration follows at once:
    // one barrier less per step.
    TeamPhase t(timers, Phase::forces);
    parallel_blocks(p.moving().begin, p.moving().end, [&](std::size_t b, std::size_t e) {
      model.compute_forces_block(p, {b, e});
      integrate_block<rot>(s, dt, {b, e}, fused_bodies);
    });
  }
  if (!fused_bodies && !s.rigid_bodies.empty()) {
    TeamPhase t(timers, Phase::rigid_bodies);
    parallel_for(0, s.rigid_bodies.size(),
                 [&](std::size_t k) { project_rigid_body(p, s.rigid_bodies[k], dt, rot); });
  }
}

// Advances `steps` steps of `dt` in one parallel region.
template <class Model>
void advance_steps(Model& model, SolverState& s, double dt, PhaseTimers& timers,
                   std::int64_t steps) {
  if (steps <= 0) return;
  const std::int64_t first = s.step;
  run_in_team([&] {
    if constexpr (Model::uses_rotation) {
      TeamPhase t(timers, Phase::half_angles);
      compute_half_angles(s.particles, s.particles.moving());
    }
    const bool fused_bodies = bodies_in_single_blocks(s);
    for (std::int64_t k = 0; k < steps; ++k)
      team_step(model, s, dt, timers, first + k, fused_bodies);
  });
  s.step = first + steps;
}

}  // namespace mpsolid
