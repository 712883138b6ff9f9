#pragma once
// A run over several MPI ranks (docs/mpi.md). Rank 0 runs the command line
// as always (the case, the set-up, the run loop, every check and output)
// and keeps a copy of the whole state; the other ranks follow it and hold
// only their part. Rank 0 sends each follower the case and its part once;
// then every rank steps its own particles (the decomposed step) in batches
// that rank 0 commands. The particles stay on their ranks between batches:
// their slices come back to rank 0 only when its checks or outputs read the
// state, and go out again only when rank 0 changed it. Rank 0's checks and
// outputs read the whole state as in a one-rank run: the same bits at any
// rank count.
//
// Every model and contact are decomposed, each rigid or loaded body owned
// by one rank.
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
#include "src/solver/distributed_step.hpp"

namespace mpsolid {

class RankedStepper {
 public:
  // Rank 0: cuts the set-up state `global`, sends every other rank its part
  // and keeps its own. Throws InputError when the case cannot be decomposed
  // (every follower is told, and waits to be released).
  RankedStepper(const CaseSpec& spec, const SolverState& global);
  // A follower: its part from rank 0. Throws InputError when rank 0 refused
  // the case.
  explicit RankedStepper(const CaseSpec& spec);
  ~RankedStepper();
  // What a batch moves between rank 0 and the ranks besides the command.
  struct Exchange {
    bool send_slices = false;  // before the steps: rank 0's copy changed
    bool bring_back = false;   // after them: rank 0 reads the state
    bool fields = false;       // and the fields of the current positions
    // Whether each rank sends rank 0 a message after the steps.
    bool answered() const { return bring_back || fields; }
  };
  // Rank 0: tells the followers; with `send_slices`, sends every rank its
  // owned slice of `global` (its particles, bodies and loads); `steps`
  // decomposed steps on every rank (0: none); with `bring_back`, the slices
  // and each rank's report come back into `global`. With `fields`, every
  // rank then runs the strain pass at the current positions and rank 0 gets
  // the whole state's strain and pressure, the strain energy and the
  // integrity check, as a one-rank refresh would give them (rank 0's
  // positions must be the ranks'). `global.step` is the ranks' step either
  // way.
  RankFields advance(SolverState& global, std::int64_t steps, Exchange how);
  // A follower's side of advance.
  void follow(std::int64_t steps, Exchange how);
  // Rank 0: every rank's times, halo cost and memory so far, as of the last
  // batch that brought the slices back, and its slices' moves, for run.json.
  std::vector<RankTimes> rank_times() const;

 private:
  // This rank's part of a batch: the steps, then (when brought back) its
  // slice and report (and fields) for rank 0.
  std::vector<double> step_and_report(std::int64_t steps, Exchange how);
  struct Parts;
  // Counts a move of rank r's slice of `doubles` values.
  void count_slice_move(int r, std::size_t doubles);
  std::unique_ptr<Parts> parts_;
  std::vector<RankTimes> rank_times_;
  struct SliceMoves {
    double moves = 0, bytes = 0;
  };
  std::vector<SliceMoves> slice_moves_;  // per rank
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
// Tells the followers to step `steps` steps and what the batch moves.
void send_command(std::int64_t steps, RankedStepper::Exchange how);
// Ends the followers: after the case, an end of steps; before it, an empty
// case. Idempotent; rank 0's main calls it on every way out.
void release();
}  // namespace followers

// A follower's whole life: receives the case, sets it up, and steps when
// told until released. Returns its exit code (0; rank 0 reports failures).
int follow_rank_zero();

}  // namespace mpsolid
