#include "src/solver/simulation.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "src/core/float_mode.hpp"
#include "src/solver/initial_motion.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/step.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

Simulation::Simulation(const CaseSpec& spec) {
  set_flush_subnormals(spec.flush_subnormals);
  TimeStepChoice choice = fix_time_step(spec, timers_);
  spec_ = std::move(choice.spec);
  stable_step_ = choice.estimate;
  state_ = choice.initial ? std::move(*choice.initial) : set_up(spec_, timers_);
  model_ = make_model(spec_.model, state_.particles, state_.bonds, spec_.model_options);
  schedule_loads(state_, spec_);
  apply_initial_motion(state_, spec_, model_info(spec_.model).uses_rotation);
  limit_speed_ = spec_.stability.max_speed * dilatational_wave_speed(spec_.materials);
  const Diagnostics start = diagnostics();
  initial_energy_ = start.kinetic_energy + start.strain_energy;
}

void Simulation::advance(std::int64_t steps) {
  set_flush_subnormals(spec_.flush_subnormals);  // the mode is process-wide: this case's choice
  std::visit([&](auto& model) { advance_steps(model, state_, spec_.dt, timers_, steps); }, model_);
}

void Simulation::refresh_fields() {
  std::visit([&](auto& model) { update_strain(model, state_, timers_); }, model_);
}

Diagnostics Simulation::current_diagnostics() {
  auto t = timers_.time(Phase::diagnostics);
  return std::visit(
      [&](const auto& model) {
        return compute_diagnostics(state_, [&](std::size_t i) {
          return model.particle_strain_energy(state_.particles, state_.bonds, i);
        });
      },
      model_);
}

Diagnostics Simulation::diagnostics() {
  refresh_fields();
  return current_diagnostics();
}

StabilityVerdict Simulation::check_stability(Diagnostics* diagnostics_out) {
  const ParticleStore& p = state_.particles;
  StabilityVerdict v = check_finite(p);
  if (!v.ok) return v;
  refresh_fields();
  auto t = timers_.time(Phase::diagnostics);
  const IntegrityReport integrity = std::visit(
      [&](const auto& model) {
        return model.check_integrity(p, state_.bonds, {spec_.stability.min_jacobian});
      },
      model_);
  if (integrity.failed) {
    v.ok = false;
    v.criterion = integrity.criterion;
    v.particle = integrity.particle;
    v.neighbor = integrity.neighbor;
    v.has_neighbor = integrity.neighbor != integrity.particle;
    v.value = integrity.value;
    return v;
  }
  const StabilityVerdict speed = check_speed(p, limit_speed_);
  if (!speed.ok) return speed;
  const Diagnostics d = current_diagnostics();
  if (diagnostics_out) *diagnostics_out = d;
  state_.peak_work = std::max(state_.peak_work, d.external_work);
  // Symplectic Euler's velocities lag the positions by half a step, so after
  // k steps the balance is off by about 1/(2k) of the work even in an exact
  // run: the check waits until that is 20 times below the tolerance.
  if (static_cast<double>(state_.step) < 10.0 / spec_.stability.energy_tolerance) return speed;
  StabilityVerdict energy =
      check_energy(d, initial_energy_, state_.peak_work, spec_.stability.energy_tolerance);
  energy.particle = speed.particle;  // no single culprit: name the fastest particle
  return energy;
}

}  // namespace mpsolid
