#include "src/solver/time_step_choice.hpp"

#include <fmt/format.h>

#include <cmath>

#include "kernels/model_registry.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/setup.hpp"

namespace mpsolid {

TimeStepChoice fix_time_step(const CaseSpec& spec, PhaseTimers& timers) {
  TimeStepChoice choice{spec, {}, {}};
  if (!spec.dt_auto || spec.dt > 0) return choice;
  // The initial state the estimate linearises about (it leaves it as it was).
  const SolverState& initial = choice.initial.emplace(set_up(spec, timers));
  AnyModel model = make_model(spec.model, initial.particles, initial.bonds, spec.model_options);
  {
    auto t = timers.time(Phase::setup);
    choice.estimate =
        std::visit([&](auto& m) { return estimate_stable_step(m, initial, spec.l0); }, model);
  }
  if (!(choice.estimate.dt_limit > 0))
    throw InputError(fmt::format(
        "{}: time.dt = \"auto\" needs elastic particles to estimate the stable step from; "
        "give dt in s",
        spec.source));
  // Contact stiffens the system only once bodies touch, so its bound is
  // added: the largest eigenvalue of a sum is at most the sum of the largest.
  if (const double contact = contact_omega_squared(spec, initial); contact > 0) {
    choice.estimate.omega_max =
        std::sqrt(choice.estimate.omega_max * choice.estimate.omega_max + contact);
    choice.estimate.dt_limit = 2.0 / choice.estimate.omega_max;
  }
  choice.spec.set_auto_time_step(choice.estimate.dt_limit, choice.estimate.omega_max);
  return choice;
}

}  // namespace mpsolid
