#include "src/solver/ranked_stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "src/core/float_mode.hpp"
#include "src/core/process_memory.hpp"
#include "src/distributed/bond_table_facts.hpp"
#include "src/distributed/state_slice.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/contact_copy.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/gas_outlines.hpp"
#include "src/solver/part_cut.hpp"
#include "src/solver/part_setup.hpp"
#include "src/solver/rank_rows.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

struct RankStepping {
  RankPart part;
  CaseSpec spec;  // its dt once rank 0 gives it (set_time_step)
  IntegrityLimits limits;
  StableStepEstimate estimate;  // of the last estimate's round
  // A frame's surfaces in the plane, made from the bodies' shapes at the
  // first frame this rank writes.
  std::vector<FrameSurface> surfaces;
  bool surfaces_made = false;
  RowPlacement placement;               // of the batch that writes rows
  std::unique_ptr<FrameChunks> chunks;  // rank 0's rows of a compressed frame, until written
  bool whole_on_rank_zero = true;       // false: rank 0 keeps no particle (told by a head round)
  std::size_t describe = 0;             // the particle a describe round names
  Decomposition decomposition;          // rank 0: who owns what
  std::int64_t rebuilds_reported = 0;   // this rank's contact list rebuilds
  std::vector<double> good;             // the last good slice (step first), as sent
  // With a gas: its outlines as this part holds them, their nodes' motion
  // at the last gas window's start (every rank's hosted nodes), and the
  // node forces rank 0 gives the gas loads then.
  std::vector<PressureSurface> gas_outlines;
  OutlineMotion gas_motion;
  GasNodeForces gas_forces;
};

namespace {
// With its slice, what a rank reports: the first step its contact pass
// found a pair too close (-1: none), its list rebuilds since its last
// report, its times and halo cost so far, its particles and its peak memory.
constexpr std::size_t kReportSize = 10;
void append_report(const RankPart& p, std::int64_t rebuilds, std::vector<double>& out) {
  const RankTimes& t = p.times;
  for (const double v :
       {static_cast<double>(p.local.contact.too_close.step.load()), static_cast<double>(rebuilds),
        t.contact_seconds, t.strain_seconds, t.forces_seconds, p.halo_cost.seconds,
        p.halo_cost.bytes_sent, static_cast<double>(p.layout.owned.size()),
        static_cast<double>(p.layout.size() - p.layout.owned.size()), peak_resident_bytes()})
    out.push_back(v);
}
// Reads a rank's report into the whole state's contact (the first step any
// rank found a pair too close; the rebuilds: every rank rebuilds together,
// so rank 0's count) and that rank's times.
RankTimes read_report(const std::vector<double>& in, std::size_t at, int rank,
                      ContactState& contact) {
  const auto step = static_cast<std::int64_t>(in[at]);
  const std::int64_t first = contact.too_close.step.load();
  if (step >= 0 && (first < 0 || step < first)) contact.too_close.step.store(step);
  if (rank == 0) contact.rebuilds += static_cast<std::int64_t>(in[at + 1]);
  RankTimes t;
  t.contact_seconds = in[at + 2];
  t.strain_seconds = in[at + 3];
  t.forces_seconds = in[at + 4];
  t.halo_seconds = in[at + 5];
  t.halo_bytes_sent = in[at + 6];
  t.owned = in[at + 7];
  t.ghosts = in[at + 8];
  t.peak_memory_bytes = in[at + 9];
  return t;
}

// A follower's first message: the cut, for it to set its part up from the
// case, or word that its part follows (in pieces); empty: the case was
// refused.
constexpr double kCutFollows = 0.0, kPartFollows = 1.0;
// The cut: the ranks, the pieces' starts, then their owners (none: slabs).
std::vector<double> cut_message(const Decomposition& d) {
  std::vector<double> message{kCutFollows, static_cast<double>(d.ranks()),
                              static_cast<double>(d.starts.size())};
  message.insert(message.end(), d.starts.begin(), d.starts.end());
  message.insert(message.end(), d.owners.begin(), d.owners.end());
  return message;
}
Decomposition cut_of_message(const std::vector<double>& message) {
  const auto ranks = static_cast<int>(message.at(1));
  const auto starts = static_cast<std::size_t>(message.at(2));
  Decomposition cut;
  for (std::size_t k = 0; k < starts; ++k)
    cut.starts.push_back(static_cast<std::size_t>(message.at(3 + k)));
  for (std::size_t k = 3 + starts; k < message.size(); ++k)
    cut.owners.push_back(static_cast<int>(message[k]));
  if (!cut.owners.empty()) cut.rank_count = ranks;
  return cut;
}

InputError refusal(const CaseSpec& spec, const std::string& why, int ranks) {
  return InputError(
      fmt::format("{}: {} over {} MPI ranks is not supported yet ({}); run it on one rank (without "
                  "mpirun, or with -np 1) and use --threads (docs/mpi.md)",
                  spec.source, why, ranks, spec.name));
}
}  // namespace

namespace {
// A part from rank 0 ready to step.
std::unique_ptr<RankStepping> make_parts(const CaseSpec& spec, LocalPart local) {
  auto parts = std::make_unique<RankStepping>();
  parts->spec = spec;
  parts->limits = {spec.stability.min_jacobian};
  parts->part = make_rank_part(spec, std::move(local));
  parts->rebuilds_reported = parts->part.local.contact.rebuilds;
  if (spec.gas.enabled)
    parts->gas_outlines = part_gas_outlines(spec, parts->part.local.loads, parts->part.body_ranges,
                                            parts->part.layout);
  return parts;
}

// A slice from rank 0 (the step, then the owned particles, bodies and loads)
// into this rank's part.
void take_slice(RankPart& p, const std::vector<double>& slice) {
  p.local.step = static_cast<std::int64_t>(slice.at(0));
  std::size_t at = 1;
  StateSlice::read(p.local, p.layout.owned, slice, at);
}

// Rank 0's bodies and loads inside this rank's part (the step first).
void take_items(RankPart& p, const std::vector<double>& items) {
  p.local.step = static_cast<std::int64_t>(items.at(0));
  std::size_t at = 1;
  StateSlice::read_items(p.local, p.layout.owned, items, at);
}

// Whether a fields round sends the strain and pressure arrays: for rank 0's
// copy of the particles, when it has one and the round is neither a check's
// nor a placement's.
bool field_arrays(const RankStepping& parts, Exchange how) {
  return parts.whole_on_rank_zero && !how.check && !how.write_rows;
}

// This rank's part of a batch: the steps, then (when brought back) its slice
// and report (and fields) for rank 0.
std::vector<double> step_and_report(RankStepping& parts, const Communicator& world,
                                    std::int64_t steps, Exchange how) {
  RankPart& p = parts.part;
  if (how.time_step) {
    // Rank 0's dt (the others send nothing).
    parts.spec.dt = from_rank_zero(world, parts.spec.dt);
    schedule_loads(p.local, parts.spec);
  }
  if (how.estimate) parts.estimate = estimate_part_stable_step(parts.spec, p, world);
  if (how.restore_good) take_slice(p, parts.good);
  if (how.gas_forces) {
    // Rank 0's forces (the others send nothing), the running step closed
    // at the nodes every rank shared.
    parts.gas_forces = world.all_gather(world.rank() == 0 ? parts.gas_forces : GasNodeForces{});
    give_gas_forces(parts.spec, p.local.loads, parts.gas_motion, parts.gas_forces);
  }
  if (steps > 0) advance_rank_part(p, world, parts.spec.dt, steps);
  if (how.gas_motion) parts.gas_motion = shared_outline_motion(p, parts.gas_outlines, world);
  if (how.keep_good) {
    parts.good.assign(1, static_cast<double>(p.local.step));
    StateSlice::append(p.local, p.layout.owned, parts.good);
  }
  std::vector<double> back;
  if (how.head) {
    // Rank 0 keeps no particle from now on: this rank's bodies and loads,
    // and the bond table's facts (collective).
    parts.whole_on_rank_zero = false;
    append_owned_items(p.local, p.layout, back);
    bond_table_facts(p.local.bonds, p.layout, world).append_to(back);
  }
  if (how.describe) {
    parts.describe =
        static_cast<std::size_t>(from_rank_zero(world, static_cast<double>(parts.describe)));
    if (p.layout.owns(parts.describe)) {
      const ParticleFacts f =
          ParticleFacts::of(p.local.particles, p.layout.local_of_owned(parts.describe));
      back.insert(back.end(), {1.0, static_cast<double>(f.id), static_cast<double>(f.body),
                               static_cast<double>(f.initial.size())});
      back.insert(back.end(), f.initial.begin(), f.initial.end());
      back.insert(back.end(), f.now.begin(), f.now.end());
    } else {
      back.push_back(0.0);
    }
  }
  if (how.bring_back) {
    if (parts.whole_on_rank_zero)
      StateSlice::append(p.local, p.layout.owned, back);
    else
      StateSlice::append_items(p.local, p.layout.owned, back);
  }
  if (how.bring_back || how.report) {
    append_report(p, p.local.contact.rebuilds - parts.rebuilds_reported, back);
    parts.rebuilds_reported = p.local.contact.rebuilds;
  }
  if (how.fields) append_rank_fields(p, world, parts.limits, back, field_arrays(parts, how));
  if (how.check) append_rank_check(p, world, back);
  if (how.write_rows) {
    const bool frame = parts.placement.frame();
    if (frame && p.local.particles.dimension != 3 && !parts.surfaces_made) {
      std::vector<std::pair<Kind, const Shape*>> bodies;
      for (const BodySpec& b : parts.spec.bodies) bodies.emplace_back(b.kind, &b.shape);
      parts.surfaces = frame_surfaces(bodies, p.body_ranges, parts.spec.l0);
      parts.surfaces_made = true;
    }
    if (parts.placement.content == RowPlacement::Content::compressed_frame) {
      // Rank 0 writes the chunks (RankedStepper::exchange): a follower sends
      // its rows of each, rank 0 keeps its own to read chunk by chunk.
      parts.chunks = std::make_unique<FrameChunks>(p, world, parts.surfaces, parts.placement);
      if (world.rank() != 0) {
        for (std::size_t c = 0; c < parts.chunks->chunks(); ++c)
          world.send(0, parts.chunks->rows(c));
        parts.chunks.reset();
      }
      back.insert(back.end(), {0.0, 0.0});  // as append_rank_rows: no error, no hashes
    } else {
      append_rank_rows(p, world, parts.surfaces, parts.placement, back);
    }
  }
  return back;
}

// A command is the steps and the exchange's flags in one number (-1: the
// end).
constexpr std::int64_t kExchangeFlags = 32768;
std::int64_t command_of(std::int64_t steps, Exchange how) {
  return kExchangeFlags * steps + (how.send_slices ? 1 : 0) + (how.bring_back ? 2 : 0) +
         (how.fields ? 4 : 0) + (how.check ? 8 : 0) + (how.keep_good ? 16 : 0) +
         (how.restore_good ? 32 : 0) + (how.write_rows ? 64 : 0) + (how.report ? 128 : 0) +
         (how.estimate ? 256 : 0) + (how.time_step ? 512 : 0) + (how.head ? 1024 : 0) +
         (how.describe ? 2048 : 0) + (how.send_items ? 4096 : 0) + (how.gas_forces ? 8192 : 0) +
         (how.gas_motion ? 16384 : 0);
}
std::int64_t steps_of(std::int64_t command) {
  return command / kExchangeFlags;
}
Exchange exchange_of(std::int64_t command) {
  const std::int64_t flags = command % kExchangeFlags;
  return {(flags & 1) != 0,    (flags & 2) != 0,    (flags & 4) != 0,    (flags & 8) != 0,
          (flags & 16) != 0,   (flags & 32) != 0,   (flags & 64) != 0,   (flags & 128) != 0,
          (flags & 256) != 0,  (flags & 512) != 0,  (flags & 1024) != 0, (flags & 2048) != 0,
          (flags & 4096) != 0, (flags & 8192) != 0, (flags & 16384) != 0};
}
}  // namespace

void Followers::send_case(const std::string& resolved_toml) {
  if (stage_ != Stage::before_case) throw std::logic_error("Followers: a second case");
  std::string text = resolved_toml;
  world_.broadcast(text);
  stage_ = Stage::stepping;
}

void Followers::send_command(std::int64_t steps, Exchange how) {
  if (stage_ != Stage::stepping) throw std::logic_error("Followers: steps without a case");
  std::int64_t command = command_of(steps, how);
  world_.broadcast(command);
}

void Followers::release() {
  if (stage_ == Stage::released) return;
  if (stage_ == Stage::before_case) {
    std::string none;
    world_.broadcast(none);
  } else {
    std::int64_t end = -1;
    world_.broadcast(end);
  }
  stage_ = Stage::released;
}

RankedStepper::RankedStepper(const CaseSpec& spec, const SolverState& global, Followers& followers)
    : followers_(followers) {
  const Communicator& world = followers.world();
  // The case with the step chosen (the resolved case of an automatic step
  // names it), then each follower's part.
  followers.send_case(spec.resolved_toml);
  const Decomposition decomposition = decompose_state(global, world.size());
  cut_ = {"slabs", 0.0, 0.0, 0.0, {}};
  slice_moves_.resize(static_cast<std::size_t>(world.size()));
  // Without contact (whose candidates the ranks share as they set up,
  // which rank 0's part cut from its copy would not join), each follower
  // sets its own part up from the case and the cut, which is all rank 0
  // sends. Otherwise each follower's part, built and sent one at a time
  // (rank 0 never holds two); an empty message tells a follower the case
  // was refused.
  if (!spec.contact.enabled) {
    for (int r = 1; r < world.size(); ++r) world.send(r, cut_message(decomposition));
  } else {
    for (int r = 1; r < world.size(); ++r) {
      try {
        const LocalPart part = local_part(global, decomposition, r);
        world.send(r, {kPartFollows});
        pack_local_part(part, [&](const std::vector<double>& piece) { world.send(r, piece); });
      } catch (const std::invalid_argument& e) {
        for (int rest = r; rest < world.size(); ++rest) world.send(rest, {});
        throw refusal(spec, e.what(), world.size());
      }
    }
  }
  try {
    parts_ = make_parts(spec, local_part(global, decomposition, 0));
  } catch (const std::invalid_argument& e) {
    throw refusal(spec, e.what(), world.size());
  }
  parts_->decomposition = decomposition;
  pieces_ = decomposition.pieces_by_rank();
}

RankedStepper::RankedStepper(const CaseSpec& spec, Followers& followers, SolverState& head)
    : followers_(followers) {
  const Communicator& world = followers.world();
  followers.send_case(spec.resolved_toml);
  const CaseCut chosen = cut_case(spec, world.size(), followers.cut());
  const Decomposition& cut = chosen.decomposition;
  cut_ = {chosen.kind, chosen.slab_ghosts, chosen.band_ghosts, chosen.block_ghosts, {}};
  slice_moves_.resize(static_cast<std::size_t>(world.size()));
  for (int r = 1; r < world.size(); ++r) world.send(r, cut_message(cut));
  try {
    parts_ = make_parts(spec, set_up_part(spec, cut, 0, &world));
  } catch (const std::invalid_argument& e) {
    throw refusal(spec, e.what(), world.size());
  }
  parts_->decomposition = cut;
  pieces_ = cut.pieces_by_rank();
  // The head: what every rank's part knows of the whole (the bodies'
  // ranges, the probes, the damping), then every rank's rigid bodies and
  // loads; the loads go back to the case's order.
  const SolverState& mine = parts_->part.local;
  head = SolverState{};
  head.particles.dimension = spec.dimension;
  head.body_ranges = parts_->part.body_ranges;
  head.probes = parts_->part.probes;
  head.damping = mine.damping;
  head.step = mine.step;
  if (mine.contact.enabled())
    contact_copy_ = std::make_unique<ContactCopy>(
        copy_contact_candidates(mine, parts_->part.layout, head.contact));
  exchange(head, 0, {.head = true});
  // Each rigid body once, in storage order (with a cut in pieces the
  // ranks' are interleaved, and a split body comes from each of its ranks).
  std::vector<std::string> names;
  for (const BodySpec& b : spec.bodies) names.push_back(b.name);
  merge_rigid_bodies(head, names);
  // Every part holds each pressure load (a gas load too) whole, with the
  // same running step: rank 0 keeps its own (its nodes' weights over its
  // own part, which only the ranks' steps read), over the body's global
  // range.
  for (const StepLoad& l : mine.loads) {
    if (!l.is_pressure()) continue;
    StepLoad& kept = head.loads.emplace_back(l);
    for (const LoadSpec& given : spec.loads)
      if (given.name == l.name) kept.range = head.body_ranges[static_cast<std::size_t>(given.body)];
    for (const int b : spec.gas.bodies)
      if (kGasLoadPrefix + spec.bodies[static_cast<std::size_t>(b)].name == l.name)
        kept.range = head.body_ranges[static_cast<std::size_t>(b)];
  }
  put_loads_in_case_order(spec, head.loads);
  for (const SplitRigidBody& b : parts_->part.split_rigid)
    cut_.split_rigid_bodies.push_back(b.name);
  counts_.particles = cut.starts.back();
}

RankedStepper::~RankedStepper() = default;

bool RankedStepper::holds_particles() const {
  return parts_->whole_on_rank_zero;
}

ParticleFacts RankedStepper::particle_facts(SolverState& global, std::size_t i) {
  if (holds_particles()) return Stepper::particle_facts(global, i);
  parts_->describe = i;
  exchange(global, 0, {.describe = true});
  return described_;
}

StableStepEstimate RankedStepper::estimate_stable_step(SolverState& global, const CaseSpec& spec) {
  parts_->spec = spec;
  exchange(global, 0, {.send_slices = ranks_behind_, .estimate = true});
  ranks_behind_ = false;
  return parts_->estimate;
}

void RankedStepper::set_time_step(const CaseSpec& spec) {
  parts_->spec = spec;
  SolverState none;  // no slice moves
  exchange(none, 0, {.time_step = true});
}

OutlineMotion RankedStepper::gas_outline_motion(SolverState& global,
                                                const std::vector<PressureSurface>& outlines) {
  if (holds_particles()) return Stepper::gas_outline_motion(global, outlines);
  exchange(global, 0, {.bring_back = true, .gas_motion = true});
  ranks_ahead_ = false;
  return parts_->gas_motion;
}

void RankedStepper::give_gas_forces(SolverState& global, const CaseSpec& spec,
                                    const OutlineMotion& motion, const GasNodeForces& forces) {
  if (holds_particles()) return Stepper::give_gas_forces(global, spec, motion, forces);
  mpsolid::give_gas_forces(spec, global.loads, motion, forces);
  parts_->gas_forces = forces;
  gas_forces_due_ = true;
}

void RankedStepper::advance(SolverState& global, std::int64_t steps, PhaseTimers&) {
  exchange(global, steps, {.send_slices = ranks_behind_});
  ranks_behind_ = false;
  ranks_ahead_ = ranks_ahead_ || steps > 0;
}

void RankedStepper::refresh_fields(SolverState& global, PhaseTimers& timers) {
  auto t = timers.time(Phase::strain);
  fields_ = exchange(global, 0,
                     {.send_slices = ranks_behind_, .bring_back = ranks_ahead_, .fields = true});
  ranks_behind_ = ranks_ahead_ = false;
}

CheckFigures RankedStepper::check_figures(SolverState& global, PhaseTimers& timers) {
  auto t = timers.time(Phase::strain);
  fields_ = exchange(global, 0, {.send_slices = ranks_behind_, .fields = true, .check = true});
  ranks_behind_ = false;
  if (contact_copy_) {
    // The ranks' own candidates came in rank order.
    place_moving_candidates(*contact_copy_, global.contact,
                            in_candidate_order(parts_->part.contact, check_.candidate_positions,
                                               global.particles.dimension == 3 ? 3 : 2));
    const std::int64_t first = global.contact.too_close.step.load();
    if (check_.too_close >= 0 && (first < 0 || check_.too_close < first))
      global.contact.too_close.step.store(check_.too_close);
  }
  return check_;
}

void RankedStepper::keep_good(SolverState& global) {
  exchange(global, 0, {.send_slices = ranks_behind_, .keep_good = true});
  ranks_behind_ = false;
  good_step_ = global.step;
  good_peak_work_ = global.peak_work;
}

void RankedStepper::restore_good(SolverState& global) {
  if (good_step_ < 0) throw std::logic_error("restore_good: no good state kept");
  exchange(global, 0, {.restore_good = true});
  global.peak_work = good_peak_work_;
  ranks_behind_ = false;
  ranks_ahead_ = true;  // rank 0's copy follows at its next read
}

PlacedRows RankedStepper::place_rows(SolverState& global, const RowPlacement& placement,
                                     PhaseTimers&) {
  parts_->placement = placement;
  const bool frame = placement.frame();
  const bool restore = placement.content == RowPlacement::Content::restore;
  if (restore && holds_particles())
    throw std::logic_error("RankedStepper: rows to restore beside rank 0's copy");
  const RankFields fields = exchange(
      global, 0,
      {.send_slices = ranks_behind_, .fields = frame, .write_rows = true, .send_items = restore});
  if (frame) fields_ = fields;
  ranks_behind_ = false;
  return placed_;
}

void RankedStepper::bring_to_rank_zero(SolverState& global) {
  if (!ranks_ahead_) return;
  exchange(global, 0, {.bring_back = true});
  ranks_ahead_ = false;
}

RankFields RankedStepper::exchange(SolverState& global, std::int64_t steps, Exchange how) {
  const Communicator& world = followers_.world();
  const Decomposition& d = parts_->decomposition;
  const auto pieces_of = [&](int r) -> const std::vector<Range>& {
    return pieces_[static_cast<std::size_t>(r)];
  };
  RankPart& p = parts_->part;
  how.gas_forces = std::exchange(gas_forces_due_, false);
  followers_.send_command(steps, how);
  if (how.write_rows) {
    std::string text = encode_placement(parts_->placement);
    world.broadcast(text);
  }
  if (how.send_items) {
    for (int r = 0; r < world.size(); ++r) {
      std::vector<double> items{static_cast<double>(global.step)};
      StateSlice::append_items(global, pieces_of(r), items);
      if (r == 0)
        take_items(p, items);
      else
        world.send(r, items);
    }
  }
  if (how.send_slices) {
    if (!holds_particles())
      throw std::logic_error("RankedStepper: slices to send, but rank 0 holds none");
    for (int r = 0; r < world.size(); ++r) {
      std::vector<double> slice{static_cast<double>(global.step)};
      StateSlice::append(global, pieces_of(r), slice);
      count_slice_move(r, slice.size() - 1);
      if (r == 0)  // rank 0's own slice, through the same message form
        take_slice(p, slice);
      else
        world.send(r, slice);
    }
  }
  std::vector<double> mine = step_and_report(*parts_, world, steps, how);
  global.step = p.local.step;
  std::string write_failure;  // the first rank's that could not write its rows
  if (parts_->chunks) write_failure = write_chunks(global);
  RankFields out;
  if (!how.answered()) return out;
  if (how.bring_back || how.report) rank_times_.clear();
  if (how.write_rows) placed_ = {};
  std::vector<OrderedSumPart<1>> energy_parts;
  RankChecks checks(p.extent_ranges.size());
  BondTableFacts bonds;
  for (int r = 0; r < world.size(); ++r) {
    const std::vector<double> back = r == 0 ? std::move(mine) : world.receive(r);
    std::size_t at = 0;
    if (how.head) {
      read_owned_items(back, at, global);
      bonds = BondTableFacts::read(back, at);  // the same on every rank
    }
    if (how.describe && back.at(at++) != 0.0) {
      described_.id = static_cast<std::int64_t>(back.at(at));
      described_.body = static_cast<int>(back.at(at + 1));
      const auto n = static_cast<long>(back.at(at + 2));
      const auto from = back.begin() + static_cast<long>(at + 3);
      described_.initial.assign(from, from + n);
      described_.now.assign(from + n, from + 2 * n);
      at += 3 + 2 * static_cast<std::size_t>(n);
    }
    if (how.bring_back) {
      const std::size_t first = at;
      if (parts_->whole_on_rank_zero) {
        StateSlice::read(global, pieces_of(r), back, at);
        count_slice_move(r, at - first);
      } else {
        StateSlice::read_items(global, pieces_of(r), back, at);
      }
    }
    if (how.bring_back || how.report) {
      rank_times_.push_back(read_report(back, at, r, global.contact));
      at += kReportSize;
    }
    if (how.fields)
      read_rank_fields(back, at, pieces_of(r), global.particles, energy_parts, out,
                       field_arrays(*parts_, how));
    if (how.check) checks.read(back, at, global, pieces_of(r));
    if (how.write_rows) {
      const std::string failed = read_rank_rows(back, at, r, parts_->placement, placed_);
      if (write_failure.empty()) write_failure = failed;
    }
  }
  if (!write_failure.empty()) {
    // A checkpoint the ranks cannot read is bad input (cut short, say).
    if (parts_->placement.content == RowPlacement::Content::restore)
      throw InputError(write_failure);
    throw std::runtime_error(write_failure);
  }
  if (how.head) {
    counts_.bonds = bonds;
  }
  if (how.fields) out.strain_energy = combine_ordered_sum(energy_parts)[0];
  if (how.check) check_ = checks.finish(global, d, out);
  return out;
}

std::string RankedStepper::write_chunks(const SolverState& global) {
  const Communicator& world = followers_.world();
  const std::unique_ptr<FrameChunks> chunks = std::move(parts_->chunks);
  const RowPlacement& placement = parts_->placement;
  const std::uint64_t total = placement.offsets.at(0), per_chunk = placement.offsets.at(1);
  // After a failed write every rank's rows are still received, so none waits.
  std::string failure;
  for (std::size_t c = 0; c < chunks->chunks(); ++c) {
    const std::uint64_t first = c * per_chunk;
    ChunkRows rows(global.particles.dimension, first,
                   static_cast<std::size_t>(std::min(per_chunk, total - first)));
    rows.add(chunks->rows(c));
    for (int r = 1; r < world.size(); ++r) rows.add(world.receive(r));
    if (!failure.empty()) continue;
    try {
      placement.chunk_sink(first, rows.values());
    } catch (const std::exception& e) {
      failure = fmt::format("{}: {}", placement.file, e.what());
    }
  }
  return failure;
}

void RankedStepper::count_slice_move(int r, std::size_t doubles) {
  SliceMoves& m = slice_moves_[static_cast<std::size_t>(r)];
  m.moves += 1;
  m.bytes += static_cast<double>(doubles * sizeof(double));
}

std::vector<RankTimes> RankedStepper::rank_times(SolverState& global) {
  exchange(global, 0, {.report = true});
  std::vector<RankTimes> times = rank_times_;
  for (std::size_t r = 0; r < times.size() && r < slice_moves_.size(); ++r) {
    times[r].slice_moves = slice_moves_[r].moves;
    times[r].slice_bytes = slice_moves_[r].bytes;
  }
  return times;
}

namespace {
// Bad input only a follower meets (rank 0 checked the case before sending
// it, and waits for this rank) ends the job here, so no rank hangs.
[[noreturn]] void end_job(const Communicator& world, const std::string& what) {
  fmt::print(stderr, "mpsolid: error: {}\n", what);
  world.abort(2);
}
}  // namespace

int follow_rank_zero(const Communicator& world) {
  std::string text;
  world.broadcast(text);
  if (text.empty()) return 0;  // rank 0 stopped before its case
  try {
    CaseSpec spec;
    try {
      spec = load_case_text(text, "rank 0's case");
    } catch (const InputError& e) {
      end_job(world, fmt::format("rank {} cannot read rank 0's case: {}", world.rank(), e.what()));
    }
    set_flush_subnormals(spec.flush_subnormals);
    // An empty first message: rank 0 refused the case (and reports it).
    std::vector<double> first = world.receive(0);
    std::unique_ptr<RankStepping> parts;
    if (!first.empty() && first[0] == kCutFollows) {
      // The cut: this rank sets its own part up from the case.
      const Decomposition cut = cut_of_message(first);
      try {
        parts = make_parts(spec, set_up_part(spec, cut, world.rank(), &world));
      } catch (const std::invalid_argument& e) {
        end_job(world, fmt::format("rank {}: {}", world.rank(), e.what()));
      }
    } else if (!first.empty()) {
      parts = make_parts(spec, unpack_local_part([&] { return world.receive(0); }));
    }
    for (;;) {
      std::int64_t command = 0;
      world.broadcast(command);
      if (command < 0) return parts ? 0 : 2;
      if (!parts) throw std::logic_error("steps for a refused case");
      const Exchange how = exchange_of(command);
      if (how.write_rows) {
        std::string placement;
        world.broadcast(placement);
        parts->placement = decode_placement(placement);
      }
      if (how.send_items) take_items(parts->part, world.receive(0));
      if (how.send_slices) take_slice(parts->part, world.receive(0));
      const std::vector<double> back = step_and_report(*parts, world, steps_of(command), how);
      if (how.answered()) world.send(0, back);
    }
  } catch (const InputError& e) {
    // This rank's own part is bad input (its model checks its particles,
    // which rank 0 never does).
    end_job(world, e.what());
  } catch (const std::exception& e) {
    fmt::print(stderr, "mpsolid: rank {} failed: {}\n", world.rank(), e.what());
    world.abort(1);
  }
}

}  // namespace mpsolid
