#pragma once
// The step on one rank of several (an MPI rank, docs/mpi.md, or a thread of
// one process stepping its own part, src/solver/thread_parts.hpp), for every
// model: the rank
// runs the one step order (src/solver/step.hpp) on its local state, over its
// owned particles, and before each pass that reads neighbours its ghosts get
// their owners' values through the halos the model names (share_motion,
// strain_pass). Every owned particle then computes exactly what the serial
// step computes, in the same order: the same bits at any rank count.
//
// With contact, the contact pass (src/solver/distributed_contact.hpp)
// follows the halo of motion, as it comes first in the serial step.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/halo_exchange.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/ordered_sum_parts.hpp"
#include "src/distributed/part_message.hpp"
#include "src/distributed/rank_group.hpp"
#include "src/solver/distributed_contact.hpp"
#include "src/solver/split_rigid_bodies.hpp"
#include "src/solver/step.hpp"

namespace mpsolid {

// One rank's part of a case: its particles and ghosts, its halo, its local
// state and the model made from it.
struct RankPart {
  LocalLayout layout;
  LocalHalo halo;
  SolverState local;
  RankContact contact;
  AnyModel model;
  Decomposition decomposition;       // the run's cut (what each rank owns)
  HaloCost halo_cost;                // summed over every step so far
  RankTimes times;                   // the passes' wall time, summed likewise
  std::size_t particles_in_run = 0;  // over every rank: the ordered sums' range
  std::size_t moving_begin = 0;      // the run's first moving particle (global)
  // What a history row reads (global storage indices): the elastic bodies'
  // ranges in the case's order, the probes.
  std::vector<Range> extent_ranges;
  std::vector<std::size_t> probes;
  std::vector<Range> body_ranges;  // every body's (global storage indices)
  // The rigid bodies the cut gives to more than one rank, projected over
  // the ranks.
  std::vector<SplitRigidBody> split_rigid;
  // The owned particles bonded to no ghost (local indices; empty at its
  // end when there are none): their forces read only owned fields.
  Range bonded_to_owned_only;
};

// Adds the wall time of its scope to `*seconds` (when not null), less the
// time spent meanwhile in halo exchanges (which `cost` counts).
class PassTime {
 public:
  PassTime(double* seconds, const HaloCost& cost)
      : seconds_(seconds),
        cost_(cost),
        in_halos_(cost.seconds),
        start_(std::chrono::steady_clock::now()) {}
  ~PassTime() {
    if (seconds_)
      *seconds_ +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() -
          (cost_.seconds - in_halos_);
  }
  PassTime(const PassTime&) = delete;
  PassTime& operator=(const PassTime&) = delete;

 private:
  double* seconds_;
  const HaloCost& cost_;
  double in_halos_;
  std::chrono::steady_clock::time_point start_;
};

// Every rank's `mine` concatenated in rank order (RankGroup::all_gather),
// what came from the other ranks tallied as the halo `what`.
std::vector<double> gather_shared_values(const RankGroup& world, const std::vector<double>& mine,
                                         HaloCost& cost, const char* what);

// The step on a rank's part: its owned particles, its ghosts' halos, contact
// over the ranks, each pass of a step timed without its halos (the fields
// round, Timing::off, is not a step's).
class OverRanks {
 public:
  enum class Timing { on, off };
  OverRanks(RankPart& part, const RankGroup& world, Timing timing = Timing::on)
      : halo_{part, world},
        gather_([&world, &part](const std::vector<double>& mine) {
          return gather_shared_values(world, mine, part.halo_cost, "pressure nodes");
        }),
        timed_(timing == Timing::on) {}
  Range own(const ParticleStore&) const { return halo_.part.layout.owned; }
  // The rank's one stepping thread does the serial bookkeeping of its part.
  bool leads() const { return true; }
  // Gives the ghosts their owners' values of the fields.
  struct Halo {
    RankPart& part;
    const RankGroup& world;
    void operator()(const char* name, std::initializer_list<ParticleField> fields) {
      exchange_halo(world, part.halo, name, fields, part.halo_cost);
    }
    void post(const char* name, std::initializer_list<ParticleField> fields) {
      post_halo(world, part.halo, name, fields, part.halo_cost);
    }
    void finish() { finish_halo(world, part.halo, part.halo_cost); }
  };
  Halo& halo() { return halo_; }
  // The particles of `moving` whose force reads no ghost (their bonds stay
  // among the owned), a range within it.
  Range reads_no_ghost(Range moving) const {
    const Range r = halo_.part.bonded_to_owned_only;
    const std::size_t b = std::clamp(r.begin, moving.begin, moving.end);
    return {b, std::clamp(r.end, b, moving.end)};
  }
  // How the parts of a split pressure's body share its nodes.
  const GatherParts* gather_parts() const { return &gather_; }
  void contact_pass(SolverState& s, std::int64_t step) {
    RankPart& part = halo_.part;
    rank_contact_pass(part.contact, s, part.layout, halo_.world, step, part.halo_cost);
  }
  void project_split_bodies(SolverState& s, double dt, std::int64_t step, bool with_rotation) {
    RankPart& part = halo_.part;
    if (part.split_rigid.empty()) return;
    project_split_rigid_bodies(part.split_rigid, s, part.layout, part.decomposition, halo_.world,
                               part.halo_cost, static_cast<double>(step) * dt, dt, with_rotation);
  }
  PassTime time(Phase phase) {
    RankTimes& t = halo_.part.times;
    double* seconds = !timed_                   ? nullptr
                      : phase == Phase::contact ? &t.contact_seconds
                      : phase == Phase::strain  ? &t.strain_seconds
                      : phase == Phase::forces  ? &t.forces_seconds
                                                : nullptr;
    return PassTime(seconds, halo_.part.halo_cost);
  }

 private:
  Halo halo_;  // the part and the world, which every method reads
  GatherParts gather_;
  bool timed_;
};

// The strain pass of the part's own particles at their current positions
// (half angles, the halos, the strain pass), as the serial refresh_fields
// gives them, then what rank 0's checks and outputs need of them, appended
// to `out`: the owned particles' strain and pressure, their share of the
// strain energy's ordered sum (src/distributed/ordered_sum_parts.hpp), and
// the model's integrity check
// among them (value, particle and neighbour in global storage indices,
// failed, the criterion's characters).
// Without `arrays`, the strain and pressure are left out (a check's round).
void append_rank_fields(RankPart& part, const RankGroup& world, const IntegrityLimits& limits,
                        std::vector<double>& out, bool arrays = true);

// What rank 0 reads of every rank's fields.
struct RankFields {
  double strain_energy = 0;   // the ranks' parts combined: the serial bits
  IntegrityReport integrity;  // the worst over the ranks (the first on ties)
};
// Reads one rank's fields (as append_rank_fields wrote them from `owned`,
// the rank's global storage ranges) into the whole state's strain and
// pressure, its part of the strain energy onto `energy_parts`, and its
// integrity report into `fields` when worse.
void read_rank_fields(const std::vector<double>& in, std::size_t& at,
                      const std::vector<Range>& owned, ParticleStore& global,
                      std::vector<OrderedSumPart<1>>& energy_parts, RankFields& fields,
                      bool arrays = true);

// The cut of the set-up state `global` over `ranks`, rigid bodies and
// bodies under a force kept whole, balancing `cost` per particle (null:
// particle_work).
Decomposition decompose_state(const SolverState& global, int ranks,
                              const std::vector<double>* cost = nullptr);

// A rank's part ready to step: its local part (as rank 0 sends it) with the
// model made from it.
RankPart make_rank_part(const CaseSpec& spec, LocalPart local);
// This rank's part of the set-up state `global`, cut by decompose_state
// (every rank holding `global`, as the tests do). Throws
// std::invalid_argument for a case the decomposed step does not cover.
RankPart make_rank_part(const CaseSpec& spec, const SolverState& global, const RankGroup& world);

// Advances the part by `steps` decomposed steps of dt. Its owned particles,
// bodies and loads must be current; the ghosts get their values from the
// halos before any pass reads them (with contact, the list is built first,
// from every rank's own candidates).
void advance_rank_part(RankPart& part, const RankGroup& world, double dt, std::int64_t steps);

}  // namespace mpsolid
