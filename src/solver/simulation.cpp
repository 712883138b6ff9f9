#include "src/solver/simulation.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"
#include "src/core/float_mode.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/initial_motion.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/step.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

Simulation::Simulation(const CaseSpec& spec) {
  const bool ranked = ranked_runs();
  set_flush_subnormals(spec.flush_subnormals);
  TimeStepChoice choice = fix_time_step(spec, timers_);
  spec_ = std::move(choice.spec);
  stable_step_ = choice.estimate;
  state_ = choice.initial ? std::move(*choice.initial) : set_up(spec_, timers_);
  // Over ranks, rank 0 holds the whole state but no model: the ranks' own
  // models give its fields, strain energy and integrity check.
  if (!ranked)
    model_ = make_model(spec_.model, state_.particles, state_.bonds, spec_.model_options);
  state_.contact = make_contact(spec_, state_);
  schedule_loads(state_, spec_);
  apply_initial_motion(state_, spec_, model_info(spec_.model).uses_rotation);
  limit_speed_ = spec_.stability.max_speed * dilatational_wave_speed(spec_.materials);
  if (ranked) {
    // The case with the step chosen (the resolved case of an automatic step
    // names it), then each follower's part.
    followers::send_case(spec_.resolved_toml);
    ranked_ = std::make_shared<RankedStepper>(spec_, state_);
  }
  const Diagnostics start = diagnostics();
  initial_energy_ = start.kinetic_energy + start.strain_energy + start.contact_energy;
}

void Simulation::advance(std::int64_t steps) {
  set_flush_subnormals(spec_.flush_subnormals);  // the mode is process-wide: this case's choice
  if (ranked_) {
    ranked_->advance(state_, steps, {.send_slices = ranks_behind_});
    ranks_behind_ = false;
    ranks_ahead_ = ranks_ahead_ || steps > 0;
    return;
  }
  std::visit([&](auto& model) { advance_steps(model, state_, spec_.dt, timers_, steps); }, model_);
}

void Simulation::refresh_fields() {
  if (ranked_) {
    auto t = timers_.time(Phase::strain);
    ranked_fields_ = ranked_->advance(
        state_, 0, {.send_slices = ranks_behind_, .bring_back = ranks_ahead_, .fields = true});
    ranks_behind_ = ranks_ahead_ = false;
  } else {
    std::visit([&](auto& model) { update_strain(model, state_, timers_); }, model_);
  }
  if (state_.contact.enabled()) {
    auto t = timers_.time(Phase::contact);
    refresh_contact_list(state_.contact, state_.particles, state_.bonds);
  }
}

void Simulation::bring_back() const {
  if (!ranks_ahead_) return;
  ranked_->advance(state_, 0, {.bring_back = true});
  ranks_ahead_ = false;
}

Diagnostics Simulation::current_diagnostics() {
  auto t = timers_.time(Phase::diagnostics);
  Diagnostics d =
      ranked_ ? diagnostics_with_strain_energy(state_, ranked_fields_.strain_energy)
              : std::visit(
                    [&](const auto& model) {
                      return compute_diagnostics(state_, [&](std::size_t i) {
                        return model.particle_strain_energy(state_.particles, state_.bonds, i);
                      });
                    },
                    model_);
  const ContactState& c = state_.contact;
  if (c.enabled()) {
    d.contact_energy = ordered_sum<1>(0, c.size(), [&](std::size_t a) {
      return std::array<double, 1>{contact_energy_share(c, state_.particles, a)};
    })[0];
    const double reach = contact_search_reach(spec_);
    const ClosestContact closest = closest_contact(c, state_.particles, state_.bonds, reach);
    d.contact_min_distance = closest.found ? closest.distance : reach;
  }
  return d;
}

Diagnostics Simulation::diagnostics() {
  refresh_fields();
  return current_diagnostics();
}

StabilityVerdict Simulation::check_stability(Diagnostics* diagnostics_out) {
  bring_back();
  const ParticleStore& p = state_.particles;
  StabilityVerdict v = check_finite(p);
  if (!v.ok) return v;
  refresh_fields();
  auto t = timers_.time(Phase::diagnostics);
  const IntegrityReport integrity =
      ranked_ ? ranked_fields_.integrity
              : std::visit(
                    [&](const auto& model) {
                      return model.check_integrity(p, state_.bonds, {spec_.stability.min_jacobian},
                                                   p.all());
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
  if (state_.contact.enabled()) {
    StabilityVerdict touch = check_interpenetration(state_.contact, p);
    if (!touch.ok && !touch.has_neighbor) {  // they parted again: name the closest pair now
      const ClosestContact closest =
          closest_contact(state_.contact, p, state_.bonds, contact_search_reach(spec_));
      touch.particle = closest.i;
      touch.neighbor = closest.j;
      touch.has_neighbor = closest.found;
      touch.value = closest.distance;
    }
    if (!touch.ok) return touch;
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
