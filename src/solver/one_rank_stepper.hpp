#pragma once
// The stepper of a run on one process. With one thread, the model and the
// team step (src/solver/step.hpp) on the whole state. With several, the
// threads as ranks (src/solver/thread_parts.hpp): each thread steps its own
// part, and the whole state gets the parts' particles back when it is read.
// The fields round, the strain energy and the integrity check run on the
// whole state with its model either way.
#include <memory>

#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/state_snapshot.hpp"
#include "src/solver/stepper.hpp"
#include "src/solver/thread_parts.hpp"

namespace mpsolid {

class OneRankStepper final : public Stepper {
 public:
  // The case's model, its coefficients from the set-up state's bonds.
  OneRankStepper(const CaseSpec& spec, const SolverState& state);
  ~OneRankStepper() override;

  StableStepEstimate estimate_stable_step(SolverState& state, const CaseSpec& spec) override;
  void set_time_step(const CaseSpec& spec) override;
  // Steps on thread_count() threads: the parts for that count (made when
  // the count changes), or the whole state with one thread.
  void advance(SolverState& state, std::int64_t steps, PhaseTimers& timers) override;
  void refresh_fields(SolverState& state, PhaseTimers& timers) override;
  double strain_energy(const SolverState& state) const override;
  IntegrityReport check_integrity(const SolverState& state,
                                  const IntegrityLimits& limits) const override;
  void bring_to_rank_zero(SolverState& state) override;
  void state_changed() override { parts_behind_ = true; }
  // With the threads' parts holding the current state, a gas window on the
  // parts (ThreadParts::gas_outline_motion): no slice moves.
  OutlineMotion gas_outline_motion(SolverState& state,
                                   const std::vector<PressureSurface>& outlines) override;
  void give_gas_forces(SolverState& state, const CaseSpec& spec, const OutlineMotion& motion,
                       const GasNodeForces& forces) override;
  void keep_good(SolverState& state) override;
  void restore_good(SolverState& state) override;
  std::int64_t good_step() const override { return good_.step; }
  std::vector<RankTimes> rank_times(SolverState&) override { return {}; }
  ThreadCrossing thread_crossing() const override;

 private:
  CaseSpec spec_;
  AnyModel model_;
  std::unique_ptr<ThreadParts> parts_;
  bool parts_ahead_ = false;   // stepped since the whole state got their particles
  bool parts_behind_ = false;  // the whole state changed since they took it
  ThreadCrossing crossing_;    // of parts made for an earlier thread count
  StateSnapshot good_;         // the last good state
};

}  // namespace mpsolid
