#pragma once
// Wall time per phase of the run, for run.json and the closing table.
#include <array>
#include <chrono>
#include <string>
#include <vector>

namespace mpsolid {

enum class Phase {
  setup,
  neighbors,
  half_angles,
  strain,
  forces,
  loads,
  integrate,
  rigid_bodies,
  diagnostics,
  output,
  contact,
  gas,
  count_
};
inline constexpr std::array<const char*, static_cast<std::size_t>(Phase::count_)> kPhaseNames = {
    "setup",     "neighbors",    "half_angles", "strain", "forces",  "loads",
    "integrate", "rigid_bodies", "diagnostics", "output", "contact", "gas"};

class PhaseTimers {
 public:
  using Clock = std::chrono::steady_clock;
  void add(Phase phase, Clock::duration d) { total_[static_cast<std::size_t>(phase)] += d; }
  double seconds(Phase phase) const {
    return std::chrono::duration<double>(total_[static_cast<std::size_t>(phase)]).count();
  }

  // Times one scope into a phase.
  class Scope {
   public:
    Scope(PhaseTimers& timers, Phase phase)
        : timers_(timers), phase_(phase), start_(Clock::now()) {}
    ~Scope() { timers_.add(phase_, Clock::now() - start_); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    PhaseTimers& timers_;
    Phase phase_;
    Clock::time_point start_;
  };
  Scope time(Phase phase) { return Scope(*this, phase); }

 private:
  std::array<Clock::duration, static_cast<std::size_t>(Phase::count_)> total_{};
};

}  // namespace mpsolid

namespace mpsolid {

// One MPI rank's share of a run's stepping (docs/mpi.md), for run.json:
// wall seconds in its passes (communication excluded) and in its halo
// exchanges (waits for slower ranks included), the bytes it sent, its
// particles and its memory.
struct RankTimes {
  double contact_seconds = 0;  // the contact pass and its rebuilds
  double strain_seconds = 0;   // the strain pass(es)
  double forces_seconds = 0;   // forces and integration
  double halo_seconds = 0;
  double halo_wait_seconds = 0;  // of halo_seconds, waiting for the others (threads as ranks)
  double halo_bytes_sent = 0;
  double owned = 0, ghosts = 0;  // particles owned, and held for its passes
  double peak_memory_bytes = 0;  // the rank's peak resident memory
  // The rank's slices of the state sent from and brought back to rank 0
  // (rank 0's own: copied), and their bytes.
  double slice_moves = 0, slice_bytes = 0;
};

// How a run over ranks is cut (src/solver/part_cut.hpp): "slabs", "bands
// along x" (y, z) or "blocks", with the ghosts each cut was estimated to
// imply, and the rigid bodies it splits between ranks.
struct CutFacts {
  std::string kind;
  double slab_ghosts = 0, band_ghosts = 0, block_ghosts = 0;
  std::vector<std::string> split_rigid_bodies;
};

// What crossed between the threads of a team stepping as ranks
// (src/solver/thread_parts.hpp), for run.json's thread facts: per step and
// summed over the threads, the values each named halo brought a thread from
// the others and the 64-byte lines they filled, and the lines of the call
// counters each call read; with each thread's part and times.
struct HaloCrossing {
  std::string name;
  double bytes = 0, lines = 0;
};
struct ThreadCrossing {
  int threads = 0;
  double steps = 0;  // steps the parts took
  std::vector<HaloCrossing> per_step;
  double calls_per_step = 0;  // the rendezvous of the team per step
  // Each rendezvous, each thread reads every other's counter line.
  double counter_lines_per_step() const { return calls_per_step * threads * (threads - 1); }
  std::vector<RankTimes> per_thread;
};

}  // namespace mpsolid
