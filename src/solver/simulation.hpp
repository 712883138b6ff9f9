#pragma once
// A case set up and ready to step: the solver state, its stepper (one rank or
// over MPI ranks, src/solver/stepper.hpp) and the phase timers, its case
// fixed (dt chosen). The run loop with outputs lives in src/app/run.hpp.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/diagnostics.hpp"
#include "src/core/gas_frame.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stability.hpp"
#include "src/core/stable_step_estimate.hpp"
#include "src/core/timers.hpp"
#include "src/solver/stepper.hpp"

namespace mpsolid {

class Followers;
class GasCoupling;

// Over MPI ranks, whether rank 0 keeps a copy of the particles and bonds:
// only where it must (`as_needed`: never, every read comes from the
// ranks), or always (`whole`: a resume from a checkpoint whose rows cannot
// be read in place, which restores the whole checkpoint there).
enum class RankZeroCopy { as_needed, whole };

class Simulation {
 public:
  // With `followers` (rank 0 of several MPI ranks: src/solver/ranked_stepper.hpp)
  // the case steps over the ranks; without, on this process.
  explicit Simulation(const CaseSpec& spec, Followers* followers = nullptr,
                      RankZeroCopy copy = RankZeroCopy::as_needed);
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  // Advances `steps` time steps (no output). Over ranks, the particles stay
  // on their ranks until the state is next read.
  void advance(std::int64_t steps);
  // Recomputes the position-dependent fields (half angles, strain, pressure)
  // for the current state, as outputs and diagnostics need.
  void refresh_fields();
  // Energies and momenta of the current state (calls refresh_fields; over
  // ranks with no copy on rank 0, a check's round on the ranks).
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
  std::size_t particle_count() const;
  // Whether state() holds the particles and bonds (over MPI ranks, rank 0
  // may keep only the bodies, loads and probes: RankZeroCopy).
  bool holds_particles() const { return stepper_->holds_particles(); }

  const CaseSpec& spec() const { return spec_; }
  // The current state. Over ranks, the particles stepped since the last
  // read come back to rank 0 first.
  const SolverState& state();
  const ParticleStore& particles() { return state().particles; }
  // The current state, to change (a restore): over ranks, the next step
  // sends the ranks their slices of it again.
  SolverState& state_to_change();
  // A restore where rank 0 keeps no copy: `restore_head` overwrites rank
  // 0's bodies, loads and step (the state it is given holds no particle),
  // then every rank takes its bodies and loads from it and reads its own
  // particles' rows of `rows` (a checkpoint's, Content::restore); returns
  // the arrays' hashes as read.
  PlacedRows restore_without_copy(const std::function<void(SolverState&)>& restore_head,
                                  const RowPlacement& rows);
  // The current state with the fields of its positions (strain, pressure),
  // for a frame: after a check over ranks, which leaves them on the ranks,
  // the fields round runs again.
  const SolverState& state_with_fields();
  // What a history row at this step reads: after a check over ranks at this
  // step, rank 0's copy (its bodies' and loads' fields from the ranks) with
  // the readings of the ranks' shares, so that no slice moves; otherwise the
  // whole state (brought back) and no readings (they are read from it).
  struct HistorySource {
    const SolverState& state;
    const HistoryReadings* readings;
  };
  HistorySource history_source();
  // Over MPI ranks, writes a frame's or a checkpoint's particle rows in
  // place, every rank its own (a frame's at the current positions, after
  // the fields round), so that no slice moves; empty on one process.
  RowPlacer row_placer();
  // What a checkpoint reads with the placer: rank 0's copy, whose bodies,
  // loads and step are current after a check over ranks at this step (else
  // the state is brought back first), and row_placer().
  struct CheckpointSource {
    const SolverState& state;
    RowPlacer placer;
  };
  CheckpointSource checkpoint_source();
  // The bonds of the run (each once), and the bond table's hash
  // (BondTable::hash), which a checkpoint keeps.
  std::size_t bond_count() const;
  std::uint64_t bond_hash() const;
  // Particle i (global storage index) of the current state, as a
  // diagnosis names it (over ranks, from the rank that owns it).
  ParticleFacts particle_facts(std::size_t i) { return stepper_->particle_facts(state_, i); }
  // The estimate behind time.dt = "auto" (zeros when dt was given).
  const StableStepEstimate& stable_step() const { return stable_step_; }
  // The model's stable-step limit about the current state, estimated where
  // it steps (set-up time): a given dt's check.
  StableStepEstimate estimate_stable_step();
  PhaseTimers& timers() { return timers_; }
  const PhaseTimers& timers() const { return timers_; }
  // Over several MPI ranks: each rank's times, halo cost and memory so far;
  // empty on one rank.
  std::vector<RankTimes> rank_times() { return stepper_->rank_times(state_); }
  // On one process with several threads: what crossed between them per
  // step (src/solver/thread_parts.hpp); threads = 0 when none stepped so.
  ThreadCrossing thread_crossing() const { return stepper_->thread_crossing(); }
  // Over several MPI ranks: how the case is cut (an empty kind on one rank).
  CutFacts rank_cut() const { return stepper_->rank_cut(); }
  // The case's gas, or nullptr without a [gas] section.
  const GasCoupling* gas() const { return gas_.get(); }
  // The gas's steps so far (-1 without a gas).
  std::int64_t gas_steps() const;
  // The gas's fields now (empty without a gas).
  GasFrame gas_frame() const;
  // Whether the gas went unphysical in an advance (which then stopped at
  // the window where it did; check_stability reports it).
  bool gas_failed() const { return !gas_failure_.empty(); }
  // The state as it is now kept as the last good one (over ranks, each rank
  // keeps its own slice), and put back (the gas too); the step it was kept at.
  void keep_good();
  void restore_good();
  std::int64_t good_step() const { return stepper_->good_step(); }
  // The gas as named arrays for a checkpoint (empty without a gas), and put
  // back from a checkpoint's (after its state's restore).
  std::vector<std::pair<std::string, std::vector<double>>> gas_saved() const;
  void restore_gas_saved(const std::vector<std::pair<std::string, std::vector<double>>>& saved);

 private:
  Diagnostics current_diagnostics();  // fields must be fresh
  // What contact's figures read: rank 0's copy of the particles, or over
  // ranks without one its copy of the candidates (of the last check's
  // round), with each one's storage index.
  struct ContactParticles {
    const ParticleStore& particles;
    const BondTable& bonds;
    const std::vector<std::uint32_t>* storage_index;  // null: the particles are the state's
  };
  ContactParticles contact_particles();
  // The contact energy and the closest pair, into `d`.
  void add_contact_figures(Diagnostics& d);
  // The gas's figures into `d`, its coupling error from each load's work
  // (a check round's readings over ranks).
  void add_gas_figures(Diagnostics& d, const std::vector<double>& load_work) const;
  // Whether a check can read the ranks' shares instead of rank 0's copy:
  // over ranks and, with contact, where rank 0 keeps a copy of the
  // candidates.
  bool checks_on_ranks() const;
  // A check's figures from rank 0's copy of the whole state (brought back),
  // and the verdicts from figures, either way (`contact` checked between
  // the integrity and the speed, on rank 0's copy of the state or of the
  // candidates).
  StabilityVerdict judge(const CheckFigures& f, Diagnostics* diagnostics_out);
  void restore_gas();  // as at the last keep_good

  CaseSpec spec_;
  PhaseTimers timers_;
  // Over ranks, rank 0's copy: current after state() or refresh_fields();
  // without the particles and bonds when the stepper keeps none there
  // (Stepper::holds_particles).
  SolverState state_;
  std::unique_ptr<Stepper> stepper_;
  std::unique_ptr<GasCoupling> gas_;
  // The gas at the last good check (GasCoupling::saved), empty until then.
  std::vector<std::pair<std::string, std::vector<double>>> gas_last_good_;
  std::string gas_failure_;  // what went unphysical, where and when
  StableStepEstimate stable_step_;
  double initial_energy_ = 0;
  double limit_speed_ = 0;
  double energy_floor_ = 0;               // the balance's round-off scale (case_energy_floor)
  bool fields_on_ranks_ = false;          // a check over ranks left rank 0's fields stale
  HistoryReadings rank_readings_;         // of the last check over ranks
  std::int64_t rank_readings_step_ = -1;  // its step
};

}  // namespace mpsolid
