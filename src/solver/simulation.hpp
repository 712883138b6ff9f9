#pragma once
// A case set up and ready to step: the solver state, the chosen model and the
// phase timers, its case fixed (dt chosen). The run loop with outputs lives in
// src/app/run.hpp.
#include <cstdint>
#include <memory>

#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/diagnostics.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stability.hpp"
#include "src/core/timers.hpp"
#include "src/solver/ranked_stepper.hpp"
#include "src/solver/stable_step.hpp"

namespace mpsolid {

class Simulation {
 public:
  // Under several MPI ranks, rank 0's simulation first sends the case to
  // the followers (src/solver/ranked_stepper.hpp).
  explicit Simulation(const CaseSpec& spec);

  // Advances `steps` time steps (no output); over several MPI ranks, every
  // rank steps its own particles (rank 0 tells the followers to), and they
  // stay there until the state is next read.
  void advance(std::int64_t steps);
  // Recomputes the position-dependent fields (half angles, strain, pressure)
  // for the current state, as outputs and diagnostics need.
  void refresh_fields();
  // Energies and momenta of the current state (calls refresh_fields).
  Diagnostics diagnostics();
  // The blow-up checks of the current state (calls refresh_fields): finite
  // values, the model's integrity (inverted bond or collapsed J), speed
  // against the dilatational wave speed, and the energy balance. The
  // diagnostics it computed come back in `diagnostics_out`.
  StabilityVerdict check_stability(Diagnostics* diagnostics_out = nullptr);
  // Sum of KE and PE at set-up, the reference of the energy balance.
  double initial_energy() const { return initial_energy_; }

  double time() const { return spec_.time_at(state_.step); }
  std::int64_t step() const { return state_.step; }

  const CaseSpec& spec() const { return spec_; }
  // The state. Over several MPI ranks, the particles stepped since the last
  // read come back to rank 0 first; after a change through the non-const
  // overloads, the next step sends the ranks their slices again.
  const SolverState& state() const {
    bring_back();
    return state_;
  }
  SolverState& state() {
    bring_back();
    ranks_behind_ = ranked_ != nullptr;
    return state_;
  }
  const ParticleStore& particles() const { return state().particles; }
  ParticleStore& particles() { return state().particles; }
  // The estimate behind time.dt = "auto" (zeros when dt was given).
  const StableStepEstimate& stable_step() const { return stable_step_; }
  PhaseTimers& timers() { return timers_; }
  // Over several MPI ranks: each rank's halo cost so far (seconds, bytes
  // sent); empty on one rank.
  std::vector<RankTimes> rank_times() const {
    return ranked_ ? ranked_->rank_times() : std::vector<RankTimes>{};
  }
  const PhaseTimers& timers() const { return timers_; }

 private:
  Diagnostics current_diagnostics();  // fields must be fresh
  // Over ranks: the particles stepped since rank 0's copy was last brought
  // back come back to it.
  void bring_back() const;

  CaseSpec spec_;
  PhaseTimers timers_;
  // Over ranks, rank 0's copy of the state: a cache of the ranks' particles,
  // brought back on a read (so a const read may fill it).
  mutable SolverState state_;
  AnyModel model_;
  StableStepEstimate stable_step_;
  double initial_energy_ = 0;
  double limit_speed_ = 0;
  std::shared_ptr<RankedStepper> ranked_;  // several MPI ranks only
  RankFields ranked_fields_;               // ... and the ranks' last fields
  mutable bool ranks_ahead_ = false;       // stepped since state_ was brought back
  bool ranks_behind_ = false;              // state_ may have changed since they got it
};

}  // namespace mpsolid
