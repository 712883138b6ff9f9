#include "src/simulation.hpp"

namespace mpsolid {

Simulation::Simulation(const CaseSpec& spec) : spec_(spec), model_(model_kind(spec.model)) {
  SetupResult setup = set_up(spec_, timers_);
  state_ = std::move(setup.state);
  body_ranges_ = std::move(setup.body_ranges);
}

void Simulation::advance(std::int64_t steps) {
  with_model(model_, [&](auto model) {
    using Model = decltype(model);
    for (std::int64_t k = 0; k < steps; ++k) advance_one_step<Model>(state_, timers_);
  });
}

void Simulation::refresh_fields() {
  with_model(model_, [&](auto model) { update_strain<decltype(model)>(state_, timers_); });
}

Diagnostics Simulation::diagnostics() {
  refresh_fields();
  auto t = timers_.time(Phase::diagnostics);
  return with_model(model_, [&](auto model) {
    using Model = decltype(model);
    return compute_diagnostics(state_, [&](std::size_t i) {
      return Model::particle_strain_energy(state_.particles, state_.bonds, i);
    });
  });
}

}  // namespace mpsolid
