#pragma once
// A run over several MPI ranks (docs/mpi.md). Rank 0 runs the command line
// as always (the case, the set-up, the run loop, every check and output);
// the other ranks follow it and hold only their part. Rank 0 sends each
// follower the case and the cut (or, with contact where rank 0 keeps a
// copy, its part) once; then every rank steps its own particles (the
// decomposed step) in batches that rank 0 commands. Rank 0 keeps no copy
// of the particles, only the bodies, loads and probes (with contact, a
// copy of the candidates; with a gas, the gas), and every read of the
// particles comes from the ranks: checks and history rows from their
// shares, frames and checkpoints written by every rank in place
// (src/solver/rank_rows.hpp), a gas window's outlines from the nodes each
// hosts (src/solver/gas_outlines.hpp), a blow-up's particle from its
// owner. A resume that restores a checkpoint whole (RankZeroCopy,
// src/solver/simulation.hpp) keeps a whole copy on rank 0 instead, whose
// slices come back only when its checks or outputs read the state and go
// out again only when it changed it. Either way: the same bits at any rank
// count.
//
// Every model and contact are decomposed, each rigid or loaded body owned
// by one rank. The command line makes rank 0's Followers; a Simulation
// given them steps through a RankedStepper.
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/communicator.hpp"
#include "src/solver/contact_copy.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/part_cut.hpp"
#include "src/solver/rank_checks.hpp"
#include "src/solver/stepper.hpp"

namespace mpsolid {

// What a batch moves between rank 0 and the ranks besides the command.
struct Exchange {
  bool send_slices = false;   // before the steps: rank 0's copy changed
  bool bring_back = false;    // after them: rank 0 reads the state
  bool fields = false;        // and the fields of the current positions
  bool check = false;         // with the fields, a check's figures instead of their arrays
  bool keep_good = false;     // each rank keeps its slice as the last good state
  bool restore_good = false;  // before the steps: each rank puts it back
  bool write_rows = false;    // each rank writes its rows of a placement (rank_rows.hpp)
  bool report = false;        // each rank's times and memory, without its slice
  bool estimate = false;      // every rank estimates the stable step on its part
  bool time_step = false;     // before the steps: rank 0 gives every rank dt
  bool head = false;          // each rank's bodies, loads and bond facts (no whole copy)
  bool describe = false;      // the owner of a particle rank 0 names describes it
  bool send_items = false;    // before the steps: rank 0's bodies and loads changed (no copy)
  bool gas_forces = false;    // before the steps: the gas's node forces to every rank's gas loads
  bool gas_motion = false;    // after them: the gas's outlines' nodes shared by every rank
  // Whether each rank sends rank 0 a message after the steps.
  bool answered() const { return bring_back || fields || write_rows || report || head || describe; }
};

// Rank 0's link to the other ranks: the case, then a command per batch, then
// their release. Made by the command line under a launcher with several
// ranks; its destructor releases the followers however rank 0 leaves.
class Followers {
 public:
  explicit Followers(const Communicator& world, CutChoice cut = CutChoice::automatic)
      : world_(world), cut_(cut) {}
  ~Followers() { release(); }
  Followers(const Followers&) = delete;
  Followers& operator=(const Followers&) = delete;

  const Communicator& world() const { return world_; }
  // How a run that sets its parts up from the case cuts it.
  CutChoice cut() const { return cut_; }
  // Sends the case (its resolved TOML) to the followers; once per run.
  void send_case(const std::string& resolved_toml);
  // Tells the followers to step `steps` steps and what the batch moves.
  void send_command(std::int64_t steps, Exchange how);
  // Ends the followers: after the case, an end of steps; before it, an
  // empty case. Idempotent.
  void release();

 private:
  enum class Stage { before_case, stepping, released };
  const Communicator& world_;
  CutChoice cut_;
  Stage stage_ = Stage::before_case;
};

// A rank's part and what stepping it needs (src/solver/ranked_stepper.cpp).
struct RankStepping;

// Rank 0's stepper over the ranks.
class RankedStepper final : public Stepper {
 public:
  // Sends the followers the case (its step maybe still to be chosen:
  // set_time_step) and cuts the set-up state `global`, sending every other
  // rank its part (or the cut, for a follower to set its part up) and
  // keeping its own. Throws InputError when the case cannot be decomposed
  // (every follower is told, and waits to be released).
  RankedStepper(const CaseSpec& spec, const SolverState& global, Followers& followers);
  // Rank 0 with no copy of the particles: every rank, rank 0 too, sets its
  // own part up from the case and a cut made from the case alone
  // (decompose_count), and `head` becomes what rank 0 keeps of the whole
  // state: every body's range, the probes, every rigid body and load (from
  // the rank that owns it), the damping. Every read of the state then comes
  // from the ranks (checks, history rows, frames, checkpoints, a blow-up's
  // particle); counts() has the particles and bonds; with contact rank 0
  // keeps a copy of the candidates (contact_copy()), and the gas's windows
  // read the outlines' nodes each rank hosts.
  RankedStepper(const CaseSpec& spec, Followers& followers, SolverState& head);
  ~RankedStepper() override;

  // Every rank estimates on its own part; each gets the one-process bits.
  StableStepEstimate estimate_stable_step(SolverState& global, const CaseSpec& spec) override;
  // Every rank steps with dt and schedules its part's loads.
  void set_time_step(const CaseSpec& spec) override;
  // Every rank steps its own particles; they stay there until rank 0 reads
  // the state (bring_to_rank_zero, refresh_fields). `global.step` follows.
  void advance(SolverState& global, std::int64_t steps, PhaseTimers& timers) override;
  // Every rank runs the strain pass at the current positions; rank 0 gets
  // the whole state's strain and pressure (and the slices stepped since the
  // last read), the strain energy and the integrity check, as a one-rank
  // refresh would give them.
  void refresh_fields(SolverState& global, PhaseTimers& timers) override;
  double strain_energy(const SolverState&) const override { return fields_.strain_energy; }
  IntegrityReport check_integrity(const SolverState&, const IntegrityLimits&) const override {
    return fields_.integrity;
  }
  void bring_to_rank_zero(SolverState& global) override;
  void state_changed() override { ranks_behind_ = true; }
  // A check's figures from the ranks' shares: no slice moves.
  bool checks_on_ranks() const override { return true; }
  CheckFigures check_figures(SolverState& global, PhaseTimers& timers) override;
  // Each rank keeps (and puts back) its own slice; no slice moves.
  void keep_good(SolverState& global) override;
  void restore_good(SolverState& global) override;
  std::int64_t good_step() const override { return good_step_; }
  // Every rank writes its own particles' rows of `placement` (a frame's
  // after the fields round at the current positions): no slice moves. A
  // restore (rank 0 keeping no copy, its bodies, loads and step restored)
  // sends every rank its bodies and loads, and each reads its own rows.
  bool places_rows() const override { return true; }
  PlacedRows place_rows(SolverState& global, const RowPlacement& placement,
                        PhaseTimers& timers) override;
  bool holds_particles() const override;
  RunCounts counts() const override { return counts_; }
  ContactCopy* contact_copy() override { return contact_copy_.get(); }
  ParticleFacts particle_facts(SolverState& global, std::size_t i) override;
  // Without a copy: the nodes each rank hosts, shared by every rank, and
  // rank 0's bodies brought up to date; the forces go to every rank's gas
  // loads with its next batch (or round).
  OutlineMotion gas_outline_motion(SolverState& global,
                                   const std::vector<PressureSurface>& outlines) override;
  void give_gas_forces(SolverState& global, const CaseSpec& spec, const OutlineMotion& motion,
                       const GasNodeForces& forces) override;
  // Each rank's report, asked now, with the slices' moves so far.
  std::vector<RankTimes> rank_times(SolverState& global) override;
  // Each rank steps with its threads forking and joining per loop.
  ThreadCrossing thread_crossing() const override { return {}; }
  CutFacts rank_cut() const override { return cut_; }

 private:
  // Tells the followers; with `send_slices`, sends every rank its owned
  // slice of `global` (its particles, bodies and loads); `steps` decomposed
  // steps on every rank (0: none); with `bring_back`, the slices and each
  // rank's report come back into `global`; with `fields`, the fields round
  // (with `check`, a check's figures into check_).
  RankFields exchange(SolverState& global, std::int64_t steps, Exchange how);
  // A compressed frame: every rank's rows chunk by chunk, each chunk written
  // by the placement's sink; what failed, or "".
  std::string write_chunks(const SolverState& global);
  // Counts a move of rank r's slice of `doubles` values.
  void count_slice_move(int r, std::size_t doubles);

  Followers& followers_;
  std::unique_ptr<RankStepping> parts_;
  std::unique_ptr<ContactCopy> contact_copy_;  // no copy of the particles, with contact
  std::vector<RankTimes> rank_times_;
  struct SliceMoves {
    double moves = 0, bytes = 0;
  };
  std::vector<SliceMoves> slice_moves_;  // per rank
  RankFields fields_;                    // of the last fields round
  CheckFigures check_;                   // of the last check's round
  PlacedRows placed_;                    // of the last placement's round
  std::int64_t good_step_ = -1;          // of the ranks' last good slices
  double good_peak_work_ = 0;
  RunCounts counts_;                        // without it, what it records of them
  CutFacts cut_;                            // how the case is cut
  std::vector<std::vector<Range>> pieces_;  // ... each rank's storage ranges
  ParticleFacts described_;                 // of the last describe round
  bool ranks_ahead_ = false;                // stepped since rank 0's copy was brought back
  bool ranks_behind_ = false;               // rank 0's copy changed since they got it
  bool gas_forces_due_ = false;             // the gas's forces wait for the ranks' next round
};

// A follower's whole life: receives the case, sets its part up, and steps
// when rank 0 tells it until released. Returns its exit code: 0, or 2 when
// rank 0 refused the case (rank 0 reports failures).
int follow_rank_zero(const Communicator& world);

}  // namespace mpsolid
