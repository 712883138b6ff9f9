#include "src/solver/one_rank_stepper.hpp"

#include <variant>

#include "src/solver/step.hpp"

namespace mpsolid {

OneRankStepper::OneRankStepper(const CaseSpec& spec, const SolverState& state)
    : model_(make_model(spec.model, state.particles, state.bonds, spec.model_options)),
      dt_(spec.dt) {}

void OneRankStepper::advance(SolverState& state, std::int64_t steps, PhaseTimers& timers) {
  std::visit([&](auto& model) { advance_steps(model, state, dt_, timers, steps); }, model_);
}

void OneRankStepper::refresh_fields(SolverState& state, PhaseTimers& timers) {
  std::visit([&](auto& model) { update_strain(model, state, timers); }, model_);
}

double OneRankStepper::strain_energy(const SolverState& state) const {
  return std::visit(
      [&](const auto& model) {
        return summed_strain_energy(model, state.particles, state.bonds, state.particles.all());
      },
      model_);
}

IntegrityReport OneRankStepper::check_integrity(const SolverState& state,
                                                const IntegrityLimits& limits) const {
  return std::visit(
      [&](const auto& model) {
        return model.check_integrity(state.particles, state.bonds, limits, state.particles.all());
      },
      model_);
}

}  // namespace mpsolid
