#pragma once
// The stepper of a run on one process: the model and the team step
// (src/solver/step.hpp) on the whole state.
#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/solver/stepper.hpp"

namespace mpsolid {

class OneRankStepper final : public Stepper {
 public:
  // The case's model, its coefficients from the set-up state's bonds.
  OneRankStepper(const CaseSpec& spec, const SolverState& state);

  void advance(SolverState& state, std::int64_t steps, PhaseTimers& timers) override;
  void refresh_fields(SolverState& state, PhaseTimers& timers) override;
  double strain_energy(const SolverState& state) const override;
  IntegrityReport check_integrity(const SolverState& state,
                                  const IntegrityLimits& limits) const override;
  void bring_to_rank_zero(SolverState&) override {}
  void state_changed() override {}
  std::vector<RankTimes> rank_times() const override { return {}; }

 private:
  AnyModel model_;
  double dt_;
};

}  // namespace mpsolid
