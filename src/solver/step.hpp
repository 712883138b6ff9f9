#pragma once
// The time step, in order, written once (MODEL.md section 2). Holds no
// physics itself:
//   (halo of motion ->) (contact pass ->) loads switch on -> strain pass (with
//   its halos) -> force/torque pass -> loads, holds, integrate, half angles ->
//   rigid-body projection (of a body split between ranks: over the ranks,
//   after the whole integration).
// Where it runs is a `Place`: OneRank (the whole state on this process; every
// halo does nothing) or OverRanks (a rank's local state, src/solver/
// distributed_step.hpp: its owned particles, its ghosts' halos and contact
// over the ranks: an MPI rank, or on one process each thread of the team,
// src/solver/thread_parts.hpp). Each model says what the halos carry before
// and after the stages of its strain pass (share_motion, strain_pass), so the
// step names no model.
//
// At OneRank a batch of steps runs in one parallel region (run_in_team):
// each phase is a loop over chunks of per-thread particle blocks that ends
// with a barrier (src/core/parallel.hpp), and the serial bookkeeping (a load
// switching on) is done by one thread. Over MPI ranks the calling thread
// runs the step and each loop forks and joins its threads (the halos are the
// calling thread's); a thread stepping its own part runs every loop alone. Loads, kick, drift and
// the new half angles of a particle follow its force in the same chunk, with no barrier between; a
// rigid body is projected by the thread that kicks its last particles. Every particle's arithmetic
// is the same at any thread and rank count, chunking and batch size: the same bits.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"
#include "src/core/damping.hpp"
#include "src/core/half_angles.hpp"
#include "src/core/integrator.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/solver_state.hpp"
#include "src/solver/step_schedule.hpp"

namespace mpsolid {

// Counts, per rigid body, its particles kicked in the current step: the
// thread that kicks the last of them projects the body (the projection reads
// all of them), whichever chunks and threads kicked the rest.
// A body split between ranks is projected by every rank holding some of it
// after the step's integration (its place's project_split_bodies): never here.
class BodyKicks {
 public:
  explicit BodyKicks(std::size_t bodies) : kicked_(bodies), split_(bodies, false) {}
  void mark_split(std::size_t k) { split_[k] = true; }
  // Adds `count` kicked particles of body k; true for the call that completes it.
  bool completes(std::size_t k, std::size_t count, std::size_t size) {
    if (split_[k]) return false;
    if (kicked_[k].fetch_add(count, std::memory_order_acq_rel) + count != size) return false;
    kicked_[k].store(0, std::memory_order_relaxed);  // read again only after the step's barrier
    return true;
  }

 private:
  std::vector<std::atomic<std::size_t>> kicked_;
  std::vector<bool> split_;
};

// Loads, holds, kick, drift and half angles of the moving particles in one
// block, and the projection of each rigid body whose last particles it kicks.
template <bool Rotation>
void integrate_block(SolverState& s, double dt, std::int64_t step, Range block, BodyKicks& kicks) {
  ParticleStore& p = s.particles;
  if (s.contact.enabled()) add_contact_forces(p, s.contact, block);
  apply_loads(p, s.loads, block);
  if (!s.holds.empty()) clear_held_forces(p, s.holds, block);
  if (s.damping.active(step)) damp_block(p, block, s.damping.coefficient, dt, Rotation);
  kick_drift(p, {block.begin, std::min(block.end, p.elastic.end)}, dt, Rotation);
  kick(p, {std::max(block.begin, p.rigid.begin), block.end}, dt, Rotation);
  for (std::size_t k = 0; k < s.rigid_bodies.size(); ++k) {
    RigidBody& body = s.rigid_bodies[k];
    const std::size_t b = std::max(block.begin, body.range.begin);
    const std::size_t e = std::min(block.end, body.range.end);
    if (b < e && kicks.completes(k, e - b, body.range.size()))
      project_rigid_body(p, body, static_cast<double>(step) * dt, dt, Rotation);
  }
}

// The contact forces of the current positions on one rank, called by every
// thread of the team. When some candidate has moved more than half the skin
// since the Verlet list was built, one thread rebuilds it and the pass runs
// again.
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

// The step on one rank: the whole state is this process's, no halo carries
// anything, the team's rank 0 times the phases.
class OneRank {
 public:
  explicit OneRank(PhaseTimers& timers) : timers_(timers) {}
  // The particles this place computes: all of them.
  Range own(const ParticleStore& p) const { return p.all(); }
  // The team's rank 0 does the serial bookkeeping.
  bool leads() const { return team_rank() == 0; }
  NoHalo& halo() { return halo_; }
  // The particles of `moving` whose force reads no ghost: all of them.
  Range reads_no_ghost(Range moving) const { return moving; }
  // Every pressure's nodes are this place's own.
  const GatherParts* gather_parts() const { return nullptr; }
  void contact_pass(SolverState& s, std::int64_t step) { mpsolid::contact_pass(s, step); }
  // Every rigid body is whole here.
  void project_split_bodies(SolverState&, double, std::int64_t, bool) {}
  TeamPhase time(Phase phase) { return TeamPhase(timers_, phase); }

 private:
  PhaseTimers& timers_;
  NoHalo halo_;
};

// The moving particles among those `place` computes.
template <class Place>
Range own_moving(Place& place, const ParticleStore& p) {
  const Range own = place.own(p);
  return {std::max(own.begin, p.moving().begin), std::min(own.end, p.moving().end)};
}

// The position-dependent fields of the current state: half angles, the
// halos of motion, the strain pass with its halos (strain and pressure, and
// the model's own fields). Walls keep theta = 0, so their half angles are
// set once.
template <class Model, class Place>
void strain_fields(Model& model, ParticleStore& p, const BondTable& bonds, Place& place) {
  if constexpr (Model::uses_rotation) {
    auto t = place.time(Phase::half_angles);
    compute_half_angles(p, own_moving(place, p));
  }
  Model::share_motion(p, place.halo());
  auto t = place.time(Phase::strain);
  model.strain_pass(p, bonds, place.own(p), place.halo());
  place.halo().finish();
}
template <class Model, class Place>
void strain_fields(Model& model, SolverState& s, Place& place) {
  strain_fields(model, s.particles, s.bonds, place);
}

// One step, in order, called by every thread of the team on one rank (by
// the one calling thread over ranks). Needs the half angles of the current
// rotations (the previous step's integration leaves them).
template <class Model, class Place>
void step_once(Model& model, SolverState& s, double dt, std::int64_t step, BodyKicks& kicks,
               Place& place) {
  ParticleStore& p = s.particles;
  constexpr bool rot = Model::uses_rotation;
  const Range moving = own_moving(place, p);
  Model::share_motion(p, place.halo());
  if (s.contact.enabled()) {
    auto t = place.time(Phase::contact);
    place.halo().finish();  // contact reads the ghosts' positions
    place.contact_pass(s, step);
  }
  {
    auto t = place.time(Phase::strain);
    // Positions stay put until the force pass, and the switch-on is read
    // only after the strain pass's closing barrier. A pressure's nodes read
    // their hosts' neighbours, ghosts included: the motion halo first.
    if (place.leads() && !s.loads.empty()) {
      if (any_pressure(s.loads)) place.halo().finish();
      serial_section([&] { activate_loads(p, s.loads, step, dt, place.gather_parts()); });
    }
    model.strain_pass(p, s.bonds, place.own(p), place.halo());
  }
  if constexpr (Model::forces_read_positions) {
    {
      auto t = place.time(Phase::forces);
      place.halo().finish();
      model.compute_forces(p, s.bonds, moving);
    }
    auto t = place.time(Phase::integrate);
    parallel_blocks(moving.begin, moving.end, [&](std::size_t b, std::size_t e) {
      integrate_block<rot>(s, dt, step, {b, e}, kicks);
    });
  } else {
    // A block's forces read no position, so its integration follows at once:
    // one barrier less per step. On a part, the particles whose forces read
    // no ghost go first, while the strain pass's last halo travels.
    auto t = place.time(Phase::forces);
    const auto forces_and_motion = [&](Range r) {
      if (r.empty()) return;
      parallel_blocks(r.begin, r.end, [&](std::size_t b, std::size_t e) {
        model.compute_forces_block(p, s.bonds, {b, e});
        integrate_block<rot>(s, dt, step, {b, e}, kicks);
      });
    };
    const Range inner = place.reads_no_ghost(moving);
    forces_and_motion(inner);
    place.halo().finish();
    forces_and_motion({moving.begin, inner.begin});
    forces_and_motion({inner.end, moving.end});
  }
  // After every particle's kick (the projection reads all of a body's).
  place.project_split_bodies(s, dt, step, rot);
}

// Advances `steps` steps of `dt` at `place` (s.step is the caller's to
// move on): the half angles of the current rotations first, then the steps.
// On one rank every thread of the team calls it, sharing `kicks`.
template <class Model, class Place>
void steps_in_order(Model& model, SolverState& s, double dt, std::int64_t steps, BodyKicks& kicks,
                    Place& place) {
  const std::int64_t first = s.step;
  if constexpr (Model::uses_rotation) {
    auto t = place.time(Phase::half_angles);
    compute_half_angles(s.particles, own_moving(place, s.particles));
  }
  for (std::int64_t k = 0; k < steps; ++k) step_once(model, s, dt, first + k, kicks, place);
}

// Advances `steps` steps of `dt` on one rank, in one parallel region.
template <class Model>
void advance_steps(Model& model, SolverState& s, double dt, PhaseTimers& timers,
                   std::int64_t steps) {
  if (steps <= 0) return;
  OneRank place(timers);
  BodyKicks kicks(s.rigid_bodies.size());
  run_in_team([&] { steps_in_order(model, s, dt, steps, kicks, place); });
  s.step += steps;
}

// The position-dependent fields on one rank (outside a team).
template <class Model>
void update_strain(Model& model, SolverState& s, PhaseTimers& timers) {
  OneRank place(timers);
  strain_fields(model, s, place);
}

}  // namespace mpsolid
