#include "src/solver/thread_parts.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <stdexcept>

#include "src/core/parallel.hpp"
#include "src/distributed/part_message.hpp"
#include "src/distributed/state_slice.hpp"
#include "src/solver/distributed_step.hpp"

namespace mpsolid {

struct ThreadPart {
  ThreadPart(RankPart p, ThreadMailboxes& boxes, int rank)
      : part(std::move(p)), ranks(boxes, rank), rebuilds_reported(part.local.contact.rebuilds) {}
  RankPart part;
  ThreadRanks ranks;
  std::int64_t rebuilds_reported;             // contact list rebuilds already given back
  std::vector<PressureSurface> gas_outlines;  // with a gas, as this part holds them
};

template <class F>
bool ThreadParts::on_each_thread(F&& f) {
  const auto size = static_cast<std::size_t>(threads());
  std::atomic<bool> whole{true};
  run_in_team([&] {
    if (team_size() != size) {  // the same on every thread: none runs f
      whole.store(false, std::memory_order_relaxed);
      return;
    }
    serial_section([&] { f(static_cast<int>(team_rank())); });
  });
  return whole.load(std::memory_order_relaxed);
}

ThreadParts::ThreadParts(const CaseSpec& spec, const SolverState& global, int threads)
    : spec_(spec),
      decomposition_(decompose_state(global, threads)),
      parts_(static_cast<std::size_t>(threads)) {
  build(global);
}

void ThreadParts::build(const SolverState& global) {
  const auto start = std::chrono::steady_clock::now();
  boxes_ = std::make_unique<ThreadMailboxes>(threads());
  steps_ = 0;
  // Building a part does no rendezvous, so a thread that fails leaves no
  // other waiting: its exception is rethrown here.
  std::vector<std::exception_ptr> failed(parts_.size());
  const bool whole = on_each_thread([&](int t) {
    try {
      parts_[static_cast<std::size_t>(t)].reset();  // its memory freed on its own thread
      auto& part = parts_[static_cast<std::size_t>(t)];
      part = std::make_unique<ThreadPart>(
          make_rank_part(spec_, local_part(global, decomposition_, t)), *boxes_, t);
      if (spec_.gas.enabled)
        part->gas_outlines = part_gas_outlines(spec_, part->part.local.loads,
                                               part->part.body_ranges, part->part.layout);
    } catch (...) {
      failed[static_cast<std::size_t>(t)] = std::current_exception();
    }
  });
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  if (!whole) throw std::runtime_error("ThreadParts: OpenMP gave a team of another size");
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ThreadParts::rebalance(SolverState& global) {
  if (recuts_ >= kRecuts) return;
  std::vector<double> busy;
  for (const std::unique_ptr<ThreadPart>& mine : parts_) {
    const RankTimes& t = mine->part.times;
    busy.push_back(t.strain_seconds + t.forces_seconds + t.contact_seconds);
  }
  const auto [least, most] = std::minmax_element(busy.begin(), busy.end());
  if (*least < std::max(kMeasureSeconds, kRecutPayback * build_seconds_)) return;
  if (*most <= kImbalance * *least) {
    recuts_ = kRecuts;  // balanced: measured no more
    return;
  }
  // Each thread's seconds spread over its particles by their work.
  const std::vector<double> work = particle_work(global.bonds);
  std::vector<double> cost(work.size());
  for (int t = 0; t < threads(); ++t) {
    const Range r = decomposition_.owned(t);
    double total = 0.0;
    for (std::size_t i = r.begin; i < r.end; ++i) total += work[i];
    for (std::size_t i = r.begin; i < r.end; ++i)
      cost[i] = work[i] * busy[static_cast<std::size_t>(t)] / total;
  }
  ++recuts_;
  const Decomposition next = decompose_state(global, threads(), &cost);
  if (next.starts != decomposition_.starts) cut_again(global, next);
}

void ThreadParts::cut_again(SolverState& global, const Decomposition& next) {
  if (next.ranks() != threads()) throw std::invalid_argument("cut_again: another thread count");
  bring_back(global);
  decomposition_ = next;
  build(global);
}

ThreadParts::~ThreadParts() = default;

bool ThreadParts::advance(SolverState& global, std::int64_t steps, bool take_slices,
                          PhaseTimers& timers) {
  const RankTimes before = parts_[0]->part.times;
  const bool whole = on_each_thread([&](int t) {
    ThreadPart& mine = *parts_[static_cast<std::size_t>(t)];
    RankPart& part = mine.part;
    if (take_slices) {
      std::vector<double> slice;
      StateSlice::append(global, decomposition_.owned(t), slice);
      std::size_t at = 0;
      StateSlice::read(part.local, part.layout.owned, slice, at);
      part.local.step = global.step;
    }
    advance_rank_part(part, mine.ranks, spec_.dt, steps);
  });
  if (!whole) return false;
  if (take_slices) {
    slice_moves_ += 1;
    slice_bytes_ += 8.0 * static_cast<double>(state_arrays(global.particles.dimension).size() *
                                              global.particles.size());
  }
  steps_ += steps;
  global.step = parts_[0]->part.local.step;
  // Thread 0's passes stand for the team's in the phase table.
  const RankTimes& after = parts_[0]->part.times;
  const auto add = [&](Phase phase, double seconds) {
    timers.add(phase, std::chrono::duration_cast<PhaseTimers::Clock::duration>(
                          std::chrono::duration<double>(seconds)));
  };
  add(Phase::contact, after.contact_seconds - before.contact_seconds);
  add(Phase::strain, after.strain_seconds - before.strain_seconds);
  add(Phase::forces, after.forces_seconds - before.forces_seconds);
  rebalance(global);
  return true;
}

void ThreadParts::bring_back(SolverState& global) {
  const auto give_back = [&](int t) {
    const RankPart& part = parts_[static_cast<std::size_t>(t)]->part;
    // The pressures' running step, the same in every part: thread 0's.
    const bool shared = t == 0;
    std::vector<double> slice;
    StateSlice::append(part.local, part.layout.owned, slice, shared);
    std::size_t at = 0;
    StateSlice::read(global, decomposition_.owned(t), slice, at, shared);
    // And what the last step left in the work arrays (half angles, strain,
    // pressure, forces), so that the whole state is the one a single thread
    // leaves, every array of it.
    const Range from = part.layout.owned;
    const std::size_t to = decomposition_.owned(t).begin;
    for_each_particle_member([&](const auto& info, auto member) {
      if (info.role != ArrayRole::work || !info.present_in(global.particles.dimension)) return;
      const auto& source = part.local.particles.*member;
      std::copy(source.begin() + static_cast<long>(from.begin),
                source.begin() + static_cast<long>(from.end),
                (global.particles.*member).begin() + static_cast<long>(to));
    });
  };
  // Each thread its own slice; on a team of another size (the thread count
  // changed since the batch), this thread every slice.
  if (!on_each_thread(give_back))
    for (int t = 0; t < threads(); ++t) give_back(t);
  slice_moves_ += 1;
  slice_bytes_ += 8.0 * static_cast<double>(state_arrays(global.particles.dimension).size() *
                                            global.particles.size());
  // Contact: the first step any part found a pair too close; the rebuilds,
  // which every part makes together, counted once.
  ContactState& contact = global.contact;
  for (std::unique_ptr<ThreadPart>& mine : parts_) {
    const std::int64_t step = mine->part.local.contact.too_close.step.load();
    const std::int64_t first = contact.too_close.step.load();
    if (step >= 0 && (first < 0 || step < first)) contact.too_close.step.store(step);
  }
  ThreadPart& lead = *parts_[0];
  contact.rebuilds += lead.part.local.contact.rebuilds - lead.rebuilds_reported;
  for (std::unique_ptr<ThreadPart>& mine : parts_)
    mine->rebuilds_reported = mine->part.local.contact.rebuilds;
}

bool ThreadParts::gas_outline_motion(OutlineMotion& motion) {
  return on_each_thread([&](int t) {
    ThreadPart& mine = *parts_[static_cast<std::size_t>(t)];
    OutlineMotion shared = shared_outline_motion(mine.part, mine.gas_outlines, mine.ranks);
    if (t == 0) motion = std::move(shared);
  });
}

bool ThreadParts::give_gas_forces(const OutlineMotion& motion, const GasNodeForces& forces) {
  return on_each_thread([&](int t) {
    mpsolid::give_gas_forces(spec_, parts_[static_cast<std::size_t>(t)]->part.local.loads, motion,
                             forces);
  });
}

ThreadCrossing ThreadParts::crossing() const {
  ThreadCrossing c;
  c.threads = threads();
  c.steps = static_cast<double>(steps_);
  if (steps_ == 0) return c;
  const double steps = c.steps;
  for (const std::unique_ptr<ThreadPart>& mine : parts_) {
    const RankPart& part = mine->part;
    for (const HaloTally& t : part.halo_cost.tallies) {
      auto at = std::find_if(c.per_step.begin(), c.per_step.end(),
                             [&](const HaloCrossing& h) { return h.name == t.name; });
      if (at == c.per_step.end()) at = c.per_step.insert(c.per_step.end(), HaloCrossing{t.name});
      at->bytes += t.bytes / steps;
      at->lines += t.lines / steps;
    }
    RankTimes times = part.times;
    times.halo_seconds = part.halo_cost.seconds;
    times.halo_wait_seconds = mine->ranks.waited_seconds();
    times.halo_bytes_sent = part.halo_cost.bytes_sent;
    times.owned = static_cast<double>(part.layout.owned.size());
    times.ghosts = static_cast<double>(part.layout.size() - part.layout.owned.size());
    times.slice_moves = slice_moves_;
    times.slice_bytes = slice_bytes_ / c.threads;
    c.per_thread.push_back(times);
  }
  double calls = 0;
  for (const HaloTally& t : parts_[0]->part.halo_cost.tallies) calls += t.calls;
  c.calls_per_step = calls / steps;
  return c;
}

}  // namespace mpsolid
