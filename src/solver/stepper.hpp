#pragma once
// How a Simulation steps its state: on this process (OneRankStepper, its
// threads as ranks when there are several) or over MPI ranks
// (RankedStepper, docs/mpi.md). The Simulation holds one of them
// and never asks which; everything that differs between the two lives in
// their implementations.
#include <cstdint>
#include <vector>

#include "kernels/model_common.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"

namespace mpsolid {

class Stepper {
 public:
  virtual ~Stepper() = default;

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
  // Each rank's times, halo cost and memory so far, for run.json (empty on
  // one rank).
  virtual std::vector<RankTimes> rank_times() const = 0;
  // With threads stepping as ranks on one process: what crossed between
  // them per step, and each thread's part (threads = 0 otherwise).
  virtual ThreadCrossing thread_crossing() const = 0;
};

}  // namespace mpsolid
