#include "src/solver/simulation.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "kernels/contact_force.hpp"
#include "kernels/model_registry.hpp"
#include "neighbor/contact_search.hpp"
#include "src/core/float_mode.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/solver/contact_copy.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/gas_coupling.hpp"
#include "src/solver/initial_motion.hpp"
#include "src/solver/one_rank_stepper.hpp"
#include "src/solver/ranked_stepper.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/time_step_choice.hpp"

namespace mpsolid {

namespace {
// The one place that chooses how a case steps, and sets `state` up: the
// whole state, or over MPI ranks where rank 0 needs no copy of it only
// what rank 0 keeps (the ranks set their parts up).
std::unique_ptr<Stepper> make_stepper(const CaseSpec& spec, SolverState& state,
                                      Followers* followers, RankZeroCopy copy,
                                      PhaseTimers& timers) {
  if (followers && copy == RankZeroCopy::as_needed) {
    auto t = timers.time(Phase::setup);
    return std::make_unique<RankedStepper>(spec, *followers, state);
  }
  state = set_up(spec, timers);
  finish_set_up(state, spec);
  if (followers) return std::make_unique<RankedStepper>(spec, state, *followers);
  return std::make_unique<OneRankStepper>(spec, state);
}
}  // namespace

Simulation::Simulation(const CaseSpec& spec, Followers* followers, RankZeroCopy copy)
    : spec_(spec) {
  set_flush_subnormals(spec.flush_subnormals);
  // Set-up reads no dt: the state and the stepper are made (over ranks,
  // every rank's part), then time.dt = "auto" is chosen by the estimate where
  // it steps, and only then are the loads scheduled.
  stepper_ = make_stepper(spec_, state_, followers, copy, timers_);
  if (needs_time_step(spec_)) {
    {
      auto t = timers_.time(Phase::setup);
      stable_step_ = stepper_->estimate_stable_step(state_, spec_);
    }
    choose_time_step(spec_, stable_step_);
  }
  schedule_loads(state_, spec_);
  stepper_->set_time_step(spec_);
  limit_speed_ = spec_.stability.max_speed * dilatational_wave_speed(spec_.materials);
  energy_floor_ = case_energy_floor(spec_, state_.body_ranges);
  if (spec_.gas.enabled) {
    gas_ = std::make_unique<GasCoupling>(spec_, state_);
    gas_->place_walls(stepper_->gas_outline_motion(state_, gas_->outlines()));
  }
  const Diagnostics start = diagnostics();
  initial_energy_ = start.kinetic_energy + start.strain_energy + start.contact_energy;
}

Simulation::~Simulation() = default;

StableStepEstimate Simulation::estimate_stable_step() {
  auto t = timers_.time(Phase::setup);
  return stepper_->estimate_stable_step(state_, spec_);
}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

void Simulation::advance(std::int64_t steps) {
  set_flush_subnormals(spec_.flush_subnormals);  // the mode is process-wide: this case's choice
  if (!gas_) {
    stepper_->advance(state_, steps, timers_);
    return;
  }
  // The solid in the gas's windows: the gas steps at each window's start.
  while (steps > 0 && !gas_failed()) {
    if (state_.step >= gas_->next_exchange()) {
      auto t = timers_.time(Phase::gas);
      const OutlineMotion now = stepper_->gas_outline_motion(state_, gas_->outlines());
      GasNodeForces forces;
      try {
        forces = gas_->window(state_, now, spec_.dt);
      } catch (const GasFailure& e) {
        gas_failure_ = fmt::format("{} in the gas step from t = {:.6g} s (step {})", e.what(),
                                   time(), state_.step);
        return;
      }
      rank_readings_step_ = -1;
      stepper_->give_gas_forces(state_, spec_, now, forces);
    }
    const std::int64_t n = std::min(steps, gas_->next_exchange() - state_.step);
    stepper_->advance(state_, n, timers_);
    steps -= n;
  }
}

void Simulation::refresh_fields() {
  stepper_->refresh_fields(state_, timers_);
  fields_on_ranks_ = false;
  if (state_.contact.enabled() && stepper_->holds_particles()) {
    auto t = timers_.time(Phase::contact);
    refresh_contact_list(state_.contact, state_.particles, state_.bonds);
  }
}

const SolverState& Simulation::state() {
  stepper_->bring_to_rank_zero(state_);
  return state_;
}

const SolverState& Simulation::state_with_fields() {
  if (fields_on_ranks_) refresh_fields();
  return state();
}

Simulation::HistorySource Simulation::history_source() {
  if (rank_readings_step_ == state_.step) return {state_, &rank_readings_};
  return {state(), nullptr};
}

RowPlacer Simulation::row_placer() {
  if (!stepper_->places_rows()) return {};
  return [this](const RowPlacement& placement) {
    PlacedRows placed = stepper_->place_rows(state_, placement, timers_);
    if (placement.frame()) fields_on_ranks_ = true;
    return placed;
  };
}

Simulation::CheckpointSource Simulation::checkpoint_source() {
  RowPlacer placer = row_placer();
  if (placer && rank_readings_step_ == state_.step) return {state_, std::move(placer)};
  return {state(), std::move(placer)};
}

SolverState& Simulation::state_to_change() {
  if (!stepper_->holds_particles())
    throw std::logic_error("state_to_change: rank 0 holds no copy of the particles");
  rank_readings_step_ = -1;
  stepper_->bring_to_rank_zero(state_);
  stepper_->state_changed();
  return state_;
}

PlacedRows Simulation::restore_without_copy(const std::function<void(SolverState&)>& restore_head,
                                            const RowPlacement& rows) {
  if (stepper_->holds_particles())
    throw std::logic_error("restore_without_copy: rank 0 holds a copy of the particles");
  restore_head(state_);
  rank_readings_step_ = -1;
  return stepper_->place_rows(state_, rows, timers_);
}

Diagnostics Simulation::current_diagnostics() {
  auto t = timers_.time(Phase::diagnostics);
  Diagnostics d = diagnostics_with_strain_energy(state_, stepper_->strain_energy(state_));
  add_contact_figures(d);
  if (gas_)
    d.gas =
        gas_->figures([&](std::size_t l) { return load_work(state_.particles, state_.loads[l]); });
  return d;
}

Simulation::ContactParticles Simulation::contact_particles() {
  if (ContactCopy* copy = stepper_->contact_copy())
    return {copy->particles, copy->bonds, &copy->storage_index};
  return {state_.particles, state_.bonds, nullptr};
}

void Simulation::add_contact_figures(Diagnostics& d) {
  ContactState& c = state_.contact;
  if (!c.enabled()) return;
  const ContactParticles on = contact_particles();
  if (on.storage_index) {
    // Rank 0's list over its copy of the candidates: not one of the run's
    // rebuilds, which the ranks count.
    const std::int64_t rebuilds = c.rebuilds;
    refresh_contact_list(c, on.particles, on.bonds);
    c.rebuilds = rebuilds;
  }
  d.contact_energy = ordered_sum<1>(0, c.size(), [&](std::size_t a) {
    return std::array<double, 1>{contact_energy_share(c, on.particles, a)};
  })[0];
  const double reach = contact_search_reach(spec_);
  const ClosestContact closest = closest_contact(c, on.particles, on.bonds, reach);
  d.contact_min_distance = closest.found ? closest.distance : reach;
}

Diagnostics Simulation::diagnostics() {
  if (!stepper_->holds_particles()) {
    // Rank 0 has no particle to read: a check's round gives the figures
    // (and the readings of a history row at this step).
    CheckFigures f = stepper_->check_figures(state_, timers_);
    fields_on_ranks_ = true;
    rank_readings_ = std::move(f.readings);
    rank_readings_step_ = state_.step;
    add_contact_figures(f.diagnostics);
    add_gas_figures(f.diagnostics, rank_readings_.load_work);
    return f.diagnostics;
  }
  refresh_fields();
  return current_diagnostics();
}

std::size_t Simulation::particle_count() const {
  return stepper_->holds_particles() ? state_.particles.size() : stepper_->counts().particles;
}

std::size_t Simulation::bond_count() const {
  return stepper_->holds_particles() ? state_.bonds.entry_count() / 2
                                     : stepper_->counts().bonds.count;
}

std::uint64_t Simulation::bond_hash() const {
  return stepper_->holds_particles() ? state_.bonds.hash() : stepper_->counts().bonds.hash;
}

std::int64_t Simulation::gas_steps() const {
  return gas_ ? gas_->steps() : -1;
}

GasFrame Simulation::gas_frame() const {
  return gas_ ? gas_->frame() : GasFrame{};
}

void Simulation::keep_good() {
  stepper_->keep_good(state_);
  // What a checkpoint keeps (the conserved fields, the walls, the balance):
  // a fifth of the solver's arrays.
  if (gas_) gas_last_good_ = gas_->saved();
}

void Simulation::restore_good() {
  rank_readings_step_ = -1;
  stepper_->restore_good(state_);
  restore_gas();
}

std::vector<std::pair<std::string, std::vector<double>>> Simulation::gas_saved() const {
  return gas_ ? gas_->saved() : GasCoupling::Saved{};
}

void Simulation::restore_gas_saved(const GasCoupling::Saved& saved) {
  if (!gas_ && saved.empty()) return;
  if (!gas_) throw InputError("the checkpoint holds a gas, the case has none");
  gas_->restore(saved);
}

void Simulation::restore_gas() {
  if (!gas_ || gas_last_good_.empty()) return;
  gas_->restore(gas_last_good_);
  gas_failure_.clear();
}

void Simulation::add_gas_figures(Diagnostics& d, const std::vector<double>& load_work) const {
  if (gas_) d.gas = gas_->figures([&](std::size_t l) { return load_work.at(l); });
}

bool Simulation::checks_on_ranks() const {
  if (!stepper_->checks_on_ranks()) return false;
  // With a whole copy, contact's figures read it.
  return !state_.contact.enabled() || stepper_->contact_copy();
}

StabilityVerdict Simulation::check_stability(Diagnostics* diagnostics_out) {
  if (gas_failed()) {
    StabilityVerdict gas;
    gas.ok = false;
    gas.criterion = "unphysical gas";
    gas.where = gas_failure_;
    return gas;
  }
  if (checks_on_ranks()) {
    fields_on_ranks_ = true;
    CheckFigures f = stepper_->check_figures(state_, timers_);
    rank_readings_ = std::move(f.readings);
    rank_readings_step_ = state_.step;
    if (f.finite.ok && !f.integrity.failed) {
      add_contact_figures(f.diagnostics);
      add_gas_figures(f.diagnostics, rank_readings_.load_work);
    }
    return judge(f, diagnostics_out);
  }
  CheckFigures f;
  const ParticleStore& p = state().particles;
  f.finite = check_finite(p);
  if (!f.finite.ok) return f.finite;
  refresh_fields();
  {
    auto t = timers_.time(Phase::diagnostics);
    f.integrity = stepper_->check_integrity(state_, {spec_.stability.min_jacobian});
    f.fastest = fastest_moving(p);
    if (!f.integrity.failed) f.diagnostics = current_diagnostics();
  }
  return judge(f, diagnostics_out);
}

StabilityVerdict Simulation::judge(const CheckFigures& f, Diagnostics* diagnostics_out) {
  if (!f.finite.ok) return f.finite;
  auto t = timers_.time(Phase::diagnostics);
  StabilityVerdict v;
  const IntegrityReport& integrity = f.integrity;
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
    const ContactParticles on = contact_particles();
    StabilityVerdict touch = check_interpenetration(state_.contact, on.particles);
    if (!touch.ok && !touch.has_neighbor) {  // they parted again: name the closest pair now
      const ClosestContact closest =
          closest_contact(state_.contact, on.particles, on.bonds, contact_search_reach(spec_));
      touch.particle = closest.i;
      touch.neighbor = closest.j;
      touch.has_neighbor = closest.found;
      touch.value = closest.distance;
    }
    if (on.storage_index && touch.has_neighbor) {
      touch.particle = on.storage_index->at(touch.particle);
      touch.neighbor = on.storage_index->at(touch.neighbor);
    }
    if (!touch.ok) return touch;
  }
  const StabilityVerdict speed = speed_verdict(f.fastest, limit_speed_);
  if (!speed.ok) return speed;
  const Diagnostics& d = f.diagnostics;
  if (diagnostics_out) *diagnostics_out = d;
  state_.peak_work = std::max(state_.peak_work, d.external_work);
  // Symplectic Euler's velocities lag the positions by half a step, so after
  // k steps the balance is off by about 1/(2k) of the work even in an exact
  // run: the check waits until that is 20 times below the tolerance.
  if (static_cast<double>(state_.step) < 10.0 / spec_.stability.energy_tolerance) return speed;
  StabilityVerdict energy = check_energy(d, initial_energy_, state_.peak_work,
                                         spec_.stability.energy_tolerance, energy_floor_);
  energy.particle = speed.particle;  // no single culprit: name the fastest particle
  return energy;
}

}  // namespace mpsolid
