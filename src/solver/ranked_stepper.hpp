#pragma once
// A run over several MPI ranks (docs/mpi.md). Rank 0 runs the command line
// as always (the case, the run loop, every check and output); the other
// ranks follow it: rank 0 sends them its case, then before each batch of
// steps the number of steps and its state. Every rank steps its own
// particles (the decomposed step); afterwards every rank holds the whole
// state again, so checks and outputs on rank 0 read it as in a one-rank
// run: the same bits at any rank count.
//
// First version: every rank keeps the whole state (memory per rank does not
// shrink yet). Every model and contact are decomposed, each rigid or loaded
// body owned by one rank.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/communicator.hpp"

namespace mpsolid {

class RankedStepper {
 public:
  // Throws InputError when the case cannot be decomposed yet.
  RankedStepper(const CaseSpec& spec, const SolverState& global);
  ~RankedStepper();
  // Every rank: rank 0's state to all, `steps` decomposed steps, the whole
  // state back on every rank.
  void advance(SolverState& global, std::int64_t steps);
  // Every rank's times and halo cost so far, gathered after each batch:
  // rank 0 reports them in run.json.
  const std::vector<RankTimes>& rank_times() const { return rank_times_; }

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
  std::vector<RankTimes> rank_times_;
};

// Whether simulations of this process step over the ranks: the command line
// turns it on under a launcher with several ranks; off, every Simulation is
// its own (as the rank tests' are).
void set_ranked_runs(bool on);
bool ranked_runs();

// Rank 0's side of the conversation with the followers.
namespace followers {
// Sends the case (its resolved TOML) to the followers; once per run.
void send_case(const std::string& resolved_toml);
// Tells the followers to step `steps` steps.
void send_steps(std::int64_t steps);
// Ends the followers: after the case, an end of steps; before it, an empty
// case. Idempotent; rank 0's main calls it on every way out.
void release();
}  // namespace followers

// A follower's whole life: receives the case, sets it up, and steps when
// told until released. Returns its exit code (0; rank 0 reports failures).
int follow_rank_zero();

}  // namespace mpsolid
