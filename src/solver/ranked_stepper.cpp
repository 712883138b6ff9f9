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
// The evolving fields of a rigid body and of a load, as doubles: what moves
// between ranks besides the particles.
constexpr std::size_t fields_of(const RigidBody*) {
  return 6;
}
void read_fields(const RigidBody& b, double* out) {
  for (const double x : {b.xg, b.yg, b.angle, b.vx, b.vy, b.omega}) *out++ = x;
}
void write_fields(RigidBody& b, const double* in) {
  for (double* x : {&b.xg, &b.yg, &b.angle, &b.vx, &b.vy, &b.omega}) *x = *in++;
}
constexpr std::size_t fields_of(const StepLoad*) {
  return 3;
}
void read_fields(const StepLoad& l, double* out) {
  out[0] = l.active ? 1.0 : 0.0;
  out[1] = l.cx_on;
  out[2] = l.cy_on;
}
void write_fields(StepLoad& l, const double* in) {
  l.active = in[0] != 0.0;
  l.cx_on = in[1];
  l.cy_on = in[2];
}

// The index of the item called `name` (rigid bodies and loads have unique names).
template <class Item>
std::size_t index_named(const std::vector<Item>& items, const std::string& name) {
  for (std::size_t k = 0; k < items.size(); ++k)
    if (items[k].name == name) return k;
  throw std::logic_error("no item named " + name);
}

// Appends every item's fields to `out`, in order.
template <class Item>
void pack_items(const std::vector<Item>& items, std::vector<double>& out) {
  for (const Item& item : items) {
    out.resize(out.size() + fields_of(&item));
    read_fields(item, out.data() + out.size() - fields_of(&item));
  }
}
// Reads every item's fields from `in` at `at`, in order.
template <class Item>
void unpack_items(std::vector<Item>& items, const std::vector<double>& in, std::size_t& at) {
  for (Item& item : items) {
    write_fields(item, in.data() + at);
    at += fields_of(&item);
  }
}

// The local items' fields from the whole state's items of the same name.
template <class Item>
void copy_to_local(const std::vector<Item>& global, std::vector<Item>& local) {
  std::vector<double> fields;
  for (Item& item : local) {
    fields.resize(fields_of(&item));
    read_fields(global[index_named(global, item.name)], fields.data());
    write_fields(item, fields.data());
  }
}

// Each rank's local items back into every rank's whole state: (index,
// fields...) records gathered in rank order.
template <class Item>
void gather_items(const std::vector<Item>& local, std::vector<Item>& global,
                  const Communicator& world) {
  const std::size_t width = 1 + fields_of(static_cast<const Item*>(nullptr));
  std::vector<double> mine;
  for (const Item& item : local) {
    mine.push_back(static_cast<double>(index_named(global, item.name)));
    mine.resize(mine.size() + width - 1);
    read_fields(item, mine.data() + mine.size() - (width - 1));
  }
  const std::vector<double> all = world.all_gather(mine);
  for (std::size_t at = 0; at + width <= all.size(); at += width)
    write_fields(global[static_cast<std::size_t>(all[at])], all.data() + at + 1);
}

// What the ranks' contact passes marked, into the whole state's contact:
// the first step any rank found a pair too close (the interpenetration
// check reports it), and the rebuilds (every rank rebuilds together).
void gather_contact_marks(const ContactState& local, std::int64_t rebuilds_before,
                          ContactState& global, const Communicator& world) {
  const std::vector<double> marks =
      world.all_gather({static_cast<double>(local.too_close.step.load())});
  for (const double m : marks) {
    const auto step = static_cast<std::int64_t>(m);
    const std::int64_t first = global.too_close.step.load();
    if (step >= 0 && (first < 0 || step < first)) global.too_close.step.store(step);
  }
  global.rebuilds += local.rebuilds - rebuilds_before;
}

// Rank 0's evolving state, as one message: the state arrays, each rigid
// body's pose and velocity, each load's switch-on, the step.
std::vector<double> pack_state(const SolverState& s) {
  std::vector<double> out;
  for (const StateArray& a : kStateArrays) {
    const std::vector<double>& v = s.particles.*a.member;
    out.insert(out.end(), v.begin(), v.end());
  }
  pack_items(s.rigid_bodies, out);
  pack_items(s.loads, out);
  out.push_back(static_cast<double>(s.step));
  return out;
}

void unpack_state(const std::vector<double>& in, SolverState& s) {
  std::size_t at = 0;
  for (const StateArray& a : kStateArrays)
    for (double& x : s.particles.*a.member) x = in[at++];
  unpack_items(s.rigid_bodies, in, at);
  unpack_items(s.loads, in, at);
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
  copy_to_local(global.rigid_bodies, p.local.rigid_bodies);
  copy_to_local(global.loads, p.local.loads);
  p.local.step = global.step;
  const std::int64_t rebuilds = p.local.contact.rebuilds;
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
  gather_items(p.local.rigid_bodies, global.rigid_bodies, world);
  gather_items(p.local.loads, global.loads, world);
  global.step = p.local.step;
  if (global.contact.enabled())
    gather_contact_marks(p.local.contact, rebuilds, global.contact, world);
  RankTimes mine = p.times;
  mine.halo_seconds = p.halo_cost.seconds;
  mine.halo_bytes_sent = p.halo_cost.bytes_sent;
  mine.owned = static_cast<double>(p.layout.owned.size());
  mine.ghosts = static_cast<double>(p.layout.size() - p.layout.owned.size());
  const std::vector<double> all =
      world.all_gather({mine.contact_seconds, mine.strain_seconds, mine.forces_seconds,
                        mine.halo_seconds, mine.halo_bytes_sent, mine.owned, mine.ghosts});
  rank_times_.clear();
  for (std::size_t at = 0; at + 7 <= all.size(); at += 7)
    rank_times_.push_back(
        {all[at], all[at + 1], all[at + 2], all[at + 3], all[at + 4], all[at + 5], all[at + 6]});
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
