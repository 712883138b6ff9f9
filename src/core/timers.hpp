#pragma once
// Wall time per phase of the run, for run.json and the closing table.
#include <array>
#include <chrono>

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
  count_
};
inline constexpr std::array<const char*, static_cast<std::size_t>(Phase::count_)> kPhaseNames = {
    "setup",     "neighbors",    "half_angles", "strain", "forces", "loads",
    "integrate", "rigid_bodies", "diagnostics", "output", "contact"};

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
