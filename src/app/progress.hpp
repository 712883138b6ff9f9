#pragma once
// Progress line on a terminal (simulated time, steps/s, ETA, the gas's steps
// beside the solid's and, with more
// than one thread, the share of the threads' time spent waiting at the
// step's barriers), redrawn at most twice a second; silent when stderr is
// not a terminal (CI, pipes).
#include <chrono>
#include <cstdint>

namespace mpsolid {

class Progress {
 public:
  Progress(std::int64_t total_steps, double dt, bool enabled, int threads);
  // `team`: the threads the last batch ran on (fewer than asked on a busy
  // machine); `gas_steps`: the gas's steps so far (-1 without a gas).
  void update(std::int64_t step, int team, std::int64_t gas_steps = -1);
  void finish();  // ends the line

 private:
  using Clock = std::chrono::steady_clock;
  std::int64_t total_;
  double dt_;
  bool enabled_;
  int threads_;
  Clock::time_point start_, last_;
  double wait_at_last_ = 0;  // team_wait_seconds() at the last redraw
  std::int64_t start_step_ = -1;
  bool drawn_ = false;
};

bool stderr_is_terminal();

}  // namespace mpsolid
