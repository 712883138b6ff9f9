#include "src/solver/one_rank_stepper.hpp"

#include <stdexcept>
#include <variant>

#include "src/core/parallel.hpp"
#include "src/solver/step.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

OneRankStepper::OneRankStepper(const CaseSpec& spec, const SolverState& state)
    : spec_(spec),
      model_(make_model(spec.model, state.particles, state.bonds, spec.model_options)) {}

OneRankStepper::~OneRankStepper() = default;

StableStepEstimate OneRankStepper::estimate_stable_step(SolverState& state, const CaseSpec& spec) {
  bring_to_rank_zero(state);
  return estimate_case_stable_step(spec, state);
}

void OneRankStepper::set_time_step(const CaseSpec& spec) {
  // Parts are made with the step they run (none yet at set-up).
  if (parts_) throw std::logic_error("set_time_step: after the threads' parts were made");
  spec_ = spec;
}

void OneRankStepper::advance(SolverState& state, std::int64_t steps, PhaseTimers& timers) {
  const int threads = thread_count();
  if (threads > 1) {
    if (!parts_ || parts_->threads() != threads) {
      bring_to_rank_zero(state);
      if (parts_) crossing_ = parts_->crossing();
      parts_.reset();  // one set of parts at a time
      parts_ = std::make_unique<ThreadParts>(spec_, state, threads);
      parts_behind_ = false;
    }
    if (parts_->advance(state, steps, parts_behind_, timers)) {
      parts_behind_ = false;
      parts_ahead_ = parts_ahead_ || steps > 0;
      return;
    }
  }
  bring_to_rank_zero(state);
  std::visit([&](auto& model) { advance_steps(model, state, spec_.dt, timers, steps); }, model_);
  parts_behind_ = parts_behind_ || steps > 0;
}

void OneRankStepper::refresh_fields(SolverState& state, PhaseTimers& timers) {
  bring_to_rank_zero(state);
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

void OneRankStepper::bring_to_rank_zero(SolverState& state) {
  if (!parts_ahead_) return;
  parts_->bring_back(state);
  parts_ahead_ = false;
}

OutlineMotion OneRankStepper::gas_outline_motion(SolverState& state,
                                                 const std::vector<PressureSurface>& outlines) {
  OutlineMotion motion;
  if (parts_ && !parts_behind_ && parts_->gas_outline_motion(motion)) return motion;
  return Stepper::gas_outline_motion(state, outlines);
}

void OneRankStepper::give_gas_forces(SolverState& state, const CaseSpec& spec,
                                     const OutlineMotion& motion, const GasNodeForces& forces) {
  if (parts_ && !parts_behind_ && parts_->give_gas_forces(motion, forces)) {
    // Ahead, the parts hold the state (the whole one takes theirs at its
    // next read); else the whole state, as current as they are, takes the
    // forces too.
    if (!parts_ahead_) mpsolid::give_gas_forces(spec, state.loads, motion, forces);
    return;
  }
  Stepper::give_gas_forces(state, spec, motion, forces);
}

void OneRankStepper::keep_good(SolverState& state) {
  bring_to_rank_zero(state);
  good_ = StateSnapshot::capture(state);
}

void OneRankStepper::restore_good(SolverState& state) {
  bring_to_rank_zero(state);
  good_.restore(state);
  state_changed();
}

ThreadCrossing OneRankStepper::thread_crossing() const {
  return parts_ ? parts_->crossing() : crossing_;
}

}  // namespace mpsolid
