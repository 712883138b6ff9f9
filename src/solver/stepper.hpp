#pragma once
// How a Simulation steps its state: on this process (OneRankStepper, its
// threads as ranks when there are several) or over MPI ranks
// (RankedStepper, docs/mpi.md). The Simulation holds one of them
// and never asks which; everything that differs between the two lives in
// their implementations.
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "kernels/model_common.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/frame_rows.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stable_step_estimate.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/bond_table_facts.hpp"
#include "src/solver/gas_outlines.hpp"
#include "src/solver/rank_checks.hpp"

namespace mpsolid {

struct ContactCopy;  // src/solver/contact_copy.hpp

// One particle as a blow-up's diagnosis names it.
struct ParticleFacts {
  std::int64_t id = 0;
  int body = 0;                 // in the case's order
  std::vector<double> initial;  // its reference position (x, y, and z in space)
  std::vector<double> now;      // its position
  static ParticleFacts of(const ParticleStore& p, std::size_t i) {
    ParticleFacts f{p.id[i], p.body[i], {p.x0[i], p.y0[i]}, {p.x[i], p.y[i]}};
    if (p.dimension == 3) {
      f.initial.push_back(p.z0[i]);
      f.now.push_back(p.z[i]);
    }
    return f;
  }
};

// What rank 0 records of the particles and bonds when it holds none of them.
struct RunCounts {
  std::size_t particles = 0;
  BondTableFacts bonds;
};

class Stepper {
 public:
  virtual ~Stepper() = default;

  // The model's stable-step limit about `state` (src/solver/
  // time_step_choice.hpp), estimated where it steps: on this process, or on
  // every rank's part.
  virtual StableStepEstimate estimate_stable_step(SolverState& state, const CaseSpec& spec) = 0;
  // The case with its time step fixed (the caller schedules its state's
  // loads): the steps follow it, and over ranks every part schedules its
  // own loads.
  virtual void set_time_step(const CaseSpec& spec) = 0;
  // Advances `state` by `steps` time steps. Over ranks, the particles stay
  // on their ranks afterwards until bring_to_rank_zero.
  virtual void advance(SolverState& state, std::int64_t steps, PhaseTimers& timers) = 0;
  // The fields round: half angles, strain and pressure of the current
  // positions, into `state`; strain_energy and check_integrity read it.
  virtual void refresh_fields(SolverState& state, PhaseTimers& timers) = 0;
  // The model's strain energy of the fields refresh_fields left.
  virtual double strain_energy(const SolverState& state) const = 0;
  // The model's integrity check (inverted bond, collapsed J) of those fields.
  virtual IntegrityReport check_integrity(const SolverState& state,
                                          const IntegrityLimits& limits) const = 0;
  // Brings the particles stepped since the last call into `state` (over
  // ranks, to rank 0; on one process, from the threads' parts).
  virtual void bring_to_rank_zero(SolverState& state) = 0;
  // `state` was changed here (a restore): the next advance gives the ranks
  // (or the threads' parts) their slices of it again.
  virtual void state_changed() = 0;
  // Whether check_figures gives a check's figures from the ranks' shares
  // (over MPI ranks), so that a check need not bring the state back.
  virtual bool checks_on_ranks() const { return false; }
  // The fields round and what a check reads (src/solver/rank_checks.hpp),
  // each rank on its own particles; `state` (rank 0's copy) is not brought
  // up to date.
  virtual CheckFigures check_figures(SolverState&, PhaseTimers&) {
    throw std::logic_error("check_figures: no ranks to ask");
  }
  // Keeps the state as it is now as the last good one (over ranks, each
  // rank its own slice), and puts it back into `state` (over ranks, into
  // every rank's part; rank 0's copy follows at its next read).
  virtual void keep_good(SolverState& state) = 0;
  virtual void restore_good(SolverState& state) = 0;
  // The step of the state keep_good kept (-1: none yet).
  virtual std::int64_t good_step() const = 0;
  // Whether place_rows writes a frame's or a checkpoint's particle rows on
  // the ranks (over MPI ranks): every rank its own particles, in place in
  // the file rank 0 laid out (a frame's at the current positions, after the
  // fields round).
  virtual bool places_rows() const { return false; }
  virtual PlacedRows place_rows(SolverState&, const RowPlacement&, PhaseTimers&) {
    throw std::logic_error("place_rows: no ranks to write");
  }
  // Whether the state the Simulation holds has the particles and bonds (on
  // one process, and over MPI ranks unless rank 0 keeps only the bodies,
  // loads and probes: then counts() has what it records of them).
  virtual bool holds_particles() const { return true; }
  virtual RunCounts counts() const { return {}; }
  // Without them, with contact: rank 0's copy of the contact candidates,
  // current after check_figures (the state's contact is over it).
  virtual ContactCopy* contact_copy() { return nullptr; }
  // Particle i (global storage index) of the current state: from `state`
  // (brought up to date), or from the rank that owns it.
  virtual ParticleFacts particle_facts(SolverState& state, std::size_t i) {
    bring_to_rank_zero(state);
    return ParticleFacts::of(state.particles, i);
  }
  // At a gas window's start: the nodes' motion of the gas's `outlines`
  // (over the whole state's storage indices), from `state` brought up to
  // date, or over ranks without a copy from the nodes each rank hosts
  // (rank 0's bodies brought up to date too).
  virtual OutlineMotion gas_outline_motion(SolverState& state,
                                           const std::vector<PressureSurface>& outlines) {
    bring_to_rank_zero(state);
    return outline_motion(state.particles, outlines);
  }
  // Then the gas's node forces to the gas loads (give_gas_forces at the
  // nodes of `motion`): in `state`, which the next advance sends out again,
  // and over ranks without a copy on every rank too, before its next steps.
  virtual void give_gas_forces(SolverState& state, const CaseSpec& spec,
                               const OutlineMotion& motion, const GasNodeForces& forces) {
    bring_to_rank_zero(state);
    mpsolid::give_gas_forces(spec, state.loads, motion, forces);
    state_changed();
  }
  // Each rank's times, halo cost and memory so far, for run.json (empty on
  // one rank).
  virtual std::vector<RankTimes> rank_times(SolverState& state) = 0;
  // With threads stepping as ranks on one process: what crossed between
  // them per step, and each thread's part (threads = 0 otherwise).
  virtual ThreadCrossing thread_crossing() const = 0;
  // Over MPI ranks: how the case is cut (an empty kind on one rank).
  virtual CutFacts rank_cut() const { return {}; }
};

}  // namespace mpsolid
