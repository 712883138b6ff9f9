#pragma once
// The step on one process with several threads: the threads as ranks
// (docs/performance.md). The state is cut as it is over MPI ranks
// (src/distributed/decomposition.hpp, rigid and loaded bodies kept whole,
// cut anywhere else), and each thread builds and steps its own part (its
// particles and one layer of ghosts, their bonds, the model made from them)
// in memory it allocated and touched first. The halos the model names go
// through the team's mailboxes (src/distributed/thread_ranks.hpp): nothing
// a thread writes in a step is written by another, and all it reads of
// another thread's writing is the halos' values and one counter per call.
// Each owned particle computes exactly what the serial step computes, in
// the same order (as over MPI ranks): the same bits at any thread count.
//
// The whole state stays the home of the particles between batches: the
// parts take their slices of it before a batch when it changed, and give
// them back when it is read (a gas window reads and sets the parts alone).
//
// The first cut balances bond entries plus particles. The threads then
// measure their passes, and while the slowest is more than kImbalance
// slower than the fastest, the state is cut again (at most kRecuts times)
// by what each thread measured, spread over its particles by the same
// count: walls that only strain, a rigid body's projection or a body's
// irregular rows cost what they cost on this machine. Any cut gives the
// same bits.
#include <cstdint>
#include <memory>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/solver/gas_outlines.hpp"

namespace mpsolid {

struct ThreadPart;  // a thread's part and its view of the team (thread_parts.cpp)

class ThreadParts {
 public:
  // Cuts `global` for `threads` threads; each thread builds its part from
  // it, on itself. Call outside a team, with `threads` the thread count.
  ThreadParts(const CaseSpec& spec, const SolverState& global, int threads);
  ~ThreadParts();
  ThreadParts(const ThreadParts&) = delete;
  ThreadParts& operator=(const ThreadParts&) = delete;

  int threads() const { return static_cast<int>(parts_.size()); }
  // The cut the parts step now, and how often the state was cut again.
  const Decomposition& decomposition() const { return decomposition_; }
  int recuts() const { return recuts_; }

  static constexpr double kImbalance = 1.05;
  static constexpr int kRecuts = 3;
  // Pass time every thread must have measured before a cut is judged: at
  // least this, and kRecutPayback times what building the parts took (so
  // that cutting again costs a short run little).
  static constexpr double kMeasureSeconds = 0.02;
  static constexpr double kRecutPayback = 20;
  // Steps `steps` steps, each thread its part; with `take_slices`, the parts
  // take their slices of `global` first. `global.step` follows. False, with
  // nothing done, when OpenMP gave a team of another size.
  bool advance(SolverState& global, std::int64_t steps, bool take_slices, PhaseTimers& timers);
  // Gives every part's slice back to `global` (with contact's counters).
  void bring_back(SolverState& global);
  // A gas window on the parts, as over MPI ranks (src/solver/
  // gas_outlines.hpp): the outlines' nodes each part hosts, shared by the
  // threads, into `motion`; then the gas's node forces to every part's gas
  // loads at those nodes. No slice moves. False, with nothing done, when
  // OpenMP gave a team of another size.
  bool gas_outline_motion(OutlineMotion& motion);
  bool give_gas_forces(const OutlineMotion& motion, const GasNodeForces& forces);
  // Cuts `global` again by `next` (same thread count): the parts' particles
  // brought back into it first, then each thread builds its new part.
  void cut_again(SolverState& global, const Decomposition& next);
  // What crossed between the threads per step, and each thread's part and
  // times, since the last cut.
  ThreadCrossing crossing() const;

 private:
  // Runs f(rank) on each thread of a team of threads(), serially within
  // each; false (nothing run) when the team has another size.
  template <class F>
  bool on_each_thread(F&& f);
  // Each thread builds its part of `global` by decomposition_ (new
  // mailboxes: every call count starts again).
  void build(const SolverState& global);
  // Cuts `global` again by the threads' measured pass times when they
  // differ by more than kImbalance (the parts' particles brought back first).
  void rebalance(SolverState& global);

  CaseSpec spec_;
  Decomposition decomposition_;
  std::unique_ptr<ThreadMailboxes> boxes_;
  std::vector<std::unique_ptr<ThreadPart>> parts_;
  int recuts_ = 0;
  double build_seconds_ = 0;  // the last build's wall time
  std::int64_t steps_ = 0;    // stepped by the parts of the current cut
  double slice_moves_ = 0, slice_bytes_ = 0;
};

}  // namespace mpsolid
