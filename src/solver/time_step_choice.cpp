#include "src/solver/time_step_choice.hpp"

#include <fmt/format.h>

#include <cmath>

#include "kernels/model_registry.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/setup.hpp"

namespace mpsolid {

StableStepEstimate estimate_case_stable_step(const CaseSpec& spec, const SolverState& initial) {
  AnyModel model = make_model(spec.model, initial.particles, initial.bonds, spec.model_options);
  StableStepEstimate e =
      std::visit([&](auto& m) { return estimate_stable_step(m, initial, spec.l0); }, model);
  if (!(e.dt_limit > 0)) return e;
  // Contact stiffens the system only once bodies touch, so its bound is
  // added: the largest eigenvalue of a sum is at most the sum of the largest.
  if (const double contact = contact_omega_squared(spec, initial); contact > 0) {
    e.omega_max = std::sqrt(e.omega_max * e.omega_max + contact);
    e.dt_limit = 2.0 / e.omega_max;
  }
  return e;
}

TimeStepChoice fix_time_step(const CaseSpec& spec, PhaseTimers& timers) {
  TimeStepChoice choice{spec, {}, {}};
  if (!spec.dt_auto || spec.dt > 0) return choice;
  // The initial state the estimate linearises about (it leaves it as it was).
  const SolverState& initial = choice.initial.emplace(set_up(spec, timers));
  {
    auto t = timers.time(Phase::setup);
    choice.estimate = estimate_case_stable_step(spec, initial);
  }
  if (!(choice.estimate.dt_limit > 0))
    throw InputError(fmt::format(
        "{}: time.dt = \"auto\" needs elastic particles to estimate the stable step from; "
        "give dt in s",
        spec.source));
  choice.spec.set_auto_time_step(choice.estimate.dt_limit, choice.estimate.omega_max);
  return choice;
}

std::string fixed_time_step_warning(const CaseSpec& spec, const SolverState& initial) {
  if (spec.dt_auto) return "";
  const StableStepEstimate e = estimate_case_stable_step(spec, initial);
  if (!(e.dt_limit > 0) || spec.dt <= e.dt_limit) return "";
  return fmt::format(
      "{}: time.dt = {:.6g} s is above the stable step estimated for the {} model on this case, "
      "{:.6g} s (2 / omega_max, {} power iterations): the run will likely go unstable within a "
      "few steps; use time.dt = \"auto\" (time.safety x that estimate) or a dt below it",
      spec.source, spec.dt, spec.model, e.dt_limit, e.iterations);
}

}  // namespace mpsolid
