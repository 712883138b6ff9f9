#pragma once
// The time step, in order (MODEL.md section 2). Holds no physics itself:
// (contact pass ->) strain pass -> (loads switch on) force/torque pass -> loads, holds,
// integrate, half angles -> rigid-body projection.
//
// A batch of steps runs in one parallel region (run_in_team): each phase is
// a loop over chunks of per-thread particle blocks that ends with a barrier
// (src/core/parallel.hpp), and the serial bookkeeping (a load switching on)
// is done by one thread. Loads, kick, drift and the new half angles of a
// particle follow its force in the same chunk, with no barrier between; a
// rigid body is projected by the thread that kicks its last particles. Every
// particle's arithmetic is the same at any thread count, chunking and batch
// size: the same bits.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"
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

// Counts, per rigid body, its particles kicked in the current step: the
// thread that kicks the last of them projects the body (the projection reads
// all of them), whichever chunks and threads kicked the rest.
class BodyKicks {
 public:
  explicit BodyKicks(std::size_t bodies) : kicked_(bodies) {}
  // Adds `count` kicked particles of body k; true for the call that completes it.
  bool completes(std::size_t k, std::size_t count, std::size_t size) {
    if (kicked_[k].fetch_add(count, std::memory_order_acq_rel) + count != size) return false;
    kicked_[k].store(0, std::memory_order_relaxed);  // read again only after the step's barrier
    return true;
  }

 private:
  std::vector<std::atomic<std::size_t>> kicked_;
};

// Loads, holds, kick, drift and half angles of the moving particles in one
// block, and the projection of each rigid body whose last particles it kicks.
template <bool Rotation>
void integrate_block(SolverState& s, double dt, Range block, BodyKicks& kicks) {
  ParticleStore& p = s.particles;
  if (s.contact.enabled()) add_contact_forces(p, s.contact, block);
  apply_loads(p, s.loads, block);
  if (!s.holds.empty()) clear_held_forces(p, s.holds, block);
  kick_drift(p, {block.begin, std::min(block.end, p.elastic.end)}, dt, Rotation);
  kick(p, {std::max(block.begin, p.rigid.begin), block.end}, dt, Rotation);
  for (std::size_t k = 0; k < s.rigid_bodies.size(); ++k) {
    RigidBody& body = s.rigid_bodies[k];
    const std::size_t b = std::max(block.begin, body.range.begin);
    const std::size_t e = std::min(block.end, body.range.end);
    if (b < e && kicks.completes(k, e - b, body.range.size()))
      project_rigid_body(p, body, dt, Rotation);
  }
}

// The contact forces of the current positions, called by every thread of the
// team. When some candidate has moved more than half the skin since the
// Verlet list was built, one thread rebuilds it and the pass runs again.
inline void contact_pass(SolverState& s, std::int64_t step) {
  ContactState& c = s.contact;
  const auto pass = [&] {
    parallel_blocks(c.first_moving, c.size(), [&](std::size_t b, std::size_t e) {
      compute_contact_forces(c, s.particles, {b, e}, step);
    });
  };
  pass();
  // Read after the pass's barrier: every thread sees the same value.
  if (c.stale.step.load(std::memory_order_relaxed) != step) return;
  parallel_blocks(0, 1,
                  [&](std::size_t, std::size_t) { build_contact_list(c, s.particles, s.bonds); });
  pass();
}

// One step, called by every thread of the team. Needs the half angles of
// the current rotations (the previous step's integration leaves them).
template <class Model>
void team_step(Model& model, SolverState& s, double dt, PhaseTimers& timers, std::int64_t step,
               BodyKicks& kicks) {
  ParticleStore& p = s.particles;
  constexpr bool rot = Model::uses_rotation;
  if (s.contact.enabled()) {
    TeamPhase t(timers, Phase::contact);
    contact_pass(s, step);
  }
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
      integrate_block<rot>(s, dt, {b, e}, kicks);
    });
  } else {
    // A block's forces read no position, so its integration follows at once:
    // one barrier less per step.
    TeamPhase t(timers, Phase::forces);
    parallel_blocks(p.moving().begin, p.moving().end, [&](std::size_t b, std::size_t e) {
      model.compute_forces_block(p, s.bonds, {b, e});
      integrate_block<rot>(s, dt, {b, e}, kicks);
    });
  }
}

// Advances `steps` steps of `dt` in one parallel region.
template <class Model>
void advance_steps(Model& model, SolverState& s, double dt, PhaseTimers& timers,
                   std::int64_t steps) {
  if (steps <= 0) return;
  const std::int64_t first = s.step;
  BodyKicks kicks(s.rigid_bodies.size());
  run_in_team([&] {
    if constexpr (Model::uses_rotation) {
      TeamPhase t(timers, Phase::half_angles);
      compute_half_angles(s.particles, s.particles.moving());
    }
    for (std::int64_t k = 0; k < steps; ++k) team_step(model, s, dt, timers, first + k, kicks);
  });
  s.step = first + steps;
}

}  // namespace mpsolid
