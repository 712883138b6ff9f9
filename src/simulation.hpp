#pragma once
// A case set up and ready to step: the solver state, the chosen model and the
// phase timers. The run loop with outputs lives in run.hpp.
#include <cstdint>

#include "src/case_spec.hpp"
#include "src/diagnostics.hpp"
#include "src/models.hpp"
#include "src/setup.hpp"

namespace mpsolid {

class Simulation {
 public:
  explicit Simulation(const CaseSpec& spec);

  // Advances `steps` time steps (no output).
  void advance(std::int64_t steps);
  // Recomputes the position-dependent fields (half angles, strain, pressure)
  // for the current state, as outputs and diagnostics need.
  void refresh_fields();
  // Energies and momenta of the current state (calls refresh_fields).
  Diagnostics diagnostics();

  double time() const { return static_cast<double>(state_.step) * state_.dt; }
  std::int64_t step() const { return state_.step; }

  const CaseSpec& spec() const { return spec_; }
  SolverState& state() { return state_; }
  const SolverState& state() const { return state_; }
  const ParticleStore& particles() const { return state_.particles; }
  ParticleStore& particles() { return state_.particles; }
  const std::vector<Range>& body_ranges() const { return body_ranges_; }
  PhaseTimers& timers() { return timers_; }
  const PhaseTimers& timers() const { return timers_; }

 private:
  CaseSpec spec_;
  ModelKind model_;
  PhaseTimers timers_;
  SolverState state_;
  std::vector<Range> body_ranges_;
};

}  // namespace mpsolid
