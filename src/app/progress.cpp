#include "src/app/progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

#include "src/core/parallel.hpp"

namespace mpsolid {

bool stderr_is_terminal() {
  return ::isatty(STDERR_FILENO) == 1;
}

Progress::Progress(std::int64_t total_steps, double dt, bool enabled, int threads)
    : total_(total_steps),
      dt_(dt),
      enabled_(enabled),
      threads_(threads),
      start_(Clock::now()),
      last_(start_),
      wait_at_last_(team_wait_seconds()) {}

void Progress::update(std::int64_t step, int team, std::int64_t gas_steps) {
  if (!enabled_) return;
  const auto now = Clock::now();
  if (start_step_ < 0) {
    start_step_ = step;
    start_ = now;
  }
  if (now - last_ < std::chrono::milliseconds(500)) return;
  const double interval = std::chrono::duration<double>(now - last_).count();
  const double wait = team_wait_seconds();
  const double wait_share = (wait - wait_at_last_) / (interval * team);
  wait_at_last_ = wait;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(step - start_step_) / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(total_ - step) / rate : 0.0;
  std::fprintf(stderr, "\r  t = %.4g ms / %.4g ms  (%5.1f %%)  %.3g steps/s  ETA %.0f s",
               1e3 * static_cast<double>(step) * dt_, 1e3 * static_cast<double>(total_) * dt_,
               100.0 * static_cast<double>(step) / static_cast<double>(total_), rate, eta);
  if (gas_steps > 0)
    std::fprintf(stderr, "  gas steps %lld (%.3g solid steps each)",
                 static_cast<long long>(gas_steps),
                 static_cast<double>(step) / static_cast<double>(gas_steps));
  // Waiting threads: an imbalance, or cores shared with other work.
  if (team > 1) std::fprintf(stderr, "  threads waiting %3.0f %%", 100.0 * wait_share);
  if (team < threads_) std::fprintf(stderr, "  (%d of %d threads: faster here)", team, threads_);
  std::fprintf(stderr, "   ");
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace mpsolid
