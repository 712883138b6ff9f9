#include "src/solver/ranked_stepper.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid {

struct RankedStepper::Parts {
  RankPart part;
  double dt = 0;
};

namespace {
// Rigid bodies and loads by name: the local state keeps the owned ones.
template <class Item>
Item* named(std::vector<Item>& items, const std::string& name) {
  for (Item& item : items)
    if (item.name == name) return &item;
  return nullptr;
}

// Rank 0's evolving state, as one message: the state arrays, each rigid
// body's pose and velocity, each load's switch-on, the step.
std::vector<double> pack_state(const SolverState& s) {
  std::vector<double> out;
  for (const StateArray& a : kStateArrays) {
    const std::vector<double>& v = s.particles.*a.member;
    out.insert(out.end(), v.begin(), v.end());
  }
  for (const RigidBody& b : s.rigid_bodies)
    out.insert(out.end(), {b.xg, b.yg, b.angle, b.vx, b.vy, b.omega});
  for (const StepLoad& l : s.loads) out.insert(out.end(), {l.active ? 1.0 : 0.0, l.cx_on, l.cy_on});
  out.push_back(static_cast<double>(s.step));
  return out;
}

void unpack_state(const std::vector<double>& in, SolverState& s) {
  std::size_t at = 0;
  for (const StateArray& a : kStateArrays)
    for (double& x : s.particles.*a.member) x = in[at++];
  for (RigidBody& b : s.rigid_bodies)
    for (double* x : {&b.xg, &b.yg, &b.angle, &b.vx, &b.vy, &b.omega}) *x = in[at++];
  for (StepLoad& l : s.loads) {
    l.active = in[at++] != 0.0;
    l.cx_on = in[at++];
    l.cy_on = in[at++];
  }
  s.step = static_cast<std::int64_t>(in[at]);
}
}  // namespace

RankedStepper::RankedStepper(const CaseSpec& spec, const SolverState& global)
    : parts_(std::make_unique<Parts>()) {
  const Communicator& world = Communicator::world();
  const auto refuse = [&](const std::string& why) {
    throw InputError(fmt::format(
        "{}: {} over {} MPI ranks is not supported yet ({}); run it on one rank (without "
        "mpirun, or with -np 1) and use --threads (docs/mpi.md)",
        spec.source, why, world.size(), spec.name));
  };
  if (spec.contact.enabled) refuse("contact");
  try {
    parts_->part = make_rank_part(spec, global, world);
  } catch (const std::invalid_argument& e) {
    refuse(e.what());
  }
  parts_->dt = spec.dt;
}

RankedStepper::~RankedStepper() = default;

void RankedStepper::advance(SolverState& global, std::int64_t steps) {
  const Communicator& world = Communicator::world();
  RankPart& p = parts_->part;
  // Rank 0's state to every rank (after a resume or a restore only rank 0 has it).
  std::vector<double> state = world.rank() == 0 ? pack_state(global) : std::vector<double>{};
  world.broadcast(state);
  if (world.rank() != 0) unpack_state(state, global);
  // The local state from it.
  for (std::size_t k = 0; k < p.layout.size(); ++k)
    for (const StateArray& a : kStateArrays)
      (p.local.particles.*a.member)[k] = (global.particles.*a.member)[p.layout.global_of[k]];
  for (RigidBody& b : p.local.rigid_bodies) {
    const RigidBody& g = *named(global.rigid_bodies, b.name);
    b.xg = g.xg, b.yg = g.yg, b.angle = g.angle, b.vx = g.vx, b.vy = g.vy, b.omega = g.omega;
  }
  for (StepLoad& l : p.local.loads) {
    const StepLoad& g = *named(global.loads, l.name);
    l.active = g.active, l.cx_on = g.cx_on, l.cy_on = g.cy_on;
  }
  p.local.step = global.step;
  advance_rank_part(p, world, parts_->dt, steps);
  // Every rank's own particles, bodies and loads back into the whole state.
  const Range owned = p.layout.owned;
  for (const StateArray& a : kStateArrays) {
    const std::vector<double>& mine = p.local.particles.*a.member;
    const std::vector<double> all =
        world.all_gather(std::vector<double>(mine.begin() + static_cast<long>(owned.begin),
                                             mine.begin() + static_cast<long>(owned.end)));
    global.particles.*a.member = all;
  }
  std::vector<double> bodies;
  for (const RigidBody& b : p.local.rigid_bodies)
    for (std::size_t k = 0; k < global.rigid_bodies.size(); ++k)
      if (global.rigid_bodies[k].name == b.name)
        bodies.insert(bodies.end(),
                      {static_cast<double>(k), b.xg, b.yg, b.angle, b.vx, b.vy, b.omega});
  const std::vector<double> all_bodies = world.all_gather(bodies);
  for (std::size_t at = 0; at + 7 <= all_bodies.size(); at += 7) {
    RigidBody& g = global.rigid_bodies[static_cast<std::size_t>(all_bodies[at])];
    g.xg = all_bodies[at + 1], g.yg = all_bodies[at + 2], g.angle = all_bodies[at + 3];
    g.vx = all_bodies[at + 4], g.vy = all_bodies[at + 5], g.omega = all_bodies[at + 6];
  }
  std::vector<double> loads;
  for (const StepLoad& l : p.local.loads)
    for (std::size_t k = 0; k < global.loads.size(); ++k)
      if (global.loads[k].name == l.name)
        loads.insert(loads.end(), {static_cast<double>(k), l.active ? 1.0 : 0.0, l.cx_on, l.cy_on});
  const std::vector<double> all_loads = world.all_gather(loads);
  for (std::size_t at = 0; at + 4 <= all_loads.size(); at += 4) {
    StepLoad& g = global.loads[static_cast<std::size_t>(all_loads[at])];
    g.active = all_loads[at + 1] != 0.0, g.cx_on = all_loads[at + 2], g.cy_on = all_loads[at + 3];
  }
  global.step = p.local.step;
  const std::vector<double> halo = world.all_gather({p.halo_cost.seconds, p.halo_cost.bytes_sent});
  rank_halo_.clear();
  for (std::size_t r = 0; r + 1 < halo.size(); r += 2)
    rank_halo_.emplace_back(halo[r], halo[r + 1]);
}

namespace {
bool ranked_runs_on = false;
}  // namespace

void set_ranked_runs(bool on) {
  ranked_runs_on = on;
}
bool ranked_runs() {
  return ranked_runs_on && Communicator::world().size() > 1;
}

namespace followers {
namespace {
enum class Stage { before_case, stepping, released };
Stage stage = Stage::before_case;
}  // namespace

void send_case(const std::string& resolved_toml) {
  std::string text = resolved_toml;
  Communicator::world().broadcast(text);
  stage = Stage::stepping;
}

void send_steps(std::int64_t steps) {
  Communicator::world().broadcast(steps);
}

void release() {
  const Communicator& world = Communicator::world();
  if (world.size() == 1 || world.rank() != 0 || stage == Stage::released) return;
  if (stage == Stage::before_case) {
    std::string none;
    world.broadcast(none);
  } else {
    std::int64_t end = -1;
    world.broadcast(end);
  }
  stage = Stage::released;
}
}  // namespace followers

int follow_rank_zero() {
  const Communicator& world = Communicator::world();
  std::string text;
  world.broadcast(text);
  if (text.empty()) return 0;  // rank 0 stopped before its case
  try {
    Simulation sim(load_case_text(text, "rank 0's case"));
    for (;;) {
      std::int64_t steps = 0;
      world.broadcast(steps);
      if (steps < 0) return 0;
      sim.advance(steps);
    }
  } catch (const InputError&) {
    return 2;  // the same error as rank 0's, which reports it
  } catch (const std::exception& e) {
    fmt::print(stderr, "mpsolid: rank {} failed: {}\n", world.rank(), e.what());
    world.abort(1);
  }
}

}  // namespace mpsolid
