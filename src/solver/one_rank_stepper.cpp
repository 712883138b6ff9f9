#include "src/solver/one_rank_stepper.hpp"

#include <array>
#include <variant>

#include "src/core/ordered_sum.hpp"
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
        return ordered_sum<1>(0, state.particles.size(), [&](std::size_t i) {
          return std::array<double, 1>{
              model.particle_strain_energy(state.particles, state.bonds, i)};
        })[0];
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
