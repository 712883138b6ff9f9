#include "src/app/thread_governor.hpp"

#include <algorithm>

namespace mpsolid {

ThreadGovernor::ThreadGovernor(int requested, bool adaptive)
    : requested_(std::max(requested, 1)), current_(requested_), adaptive_(adaptive) {}

void ThreadGovernor::record(std::int64_t steps, double seconds, double wait_seconds) {
  seconds_at_[current_] += seconds;
  if (!adaptive_ || requested_ == 1) return;
  steps_ += steps;
  seconds_ += seconds;
  wait_ += wait_seconds;
  if (seconds_ >= kWindowSeconds) end_window();
}

void ThreadGovernor::end_window() {
  const double rate = static_cast<double>(steps_) / seconds_;
  const double wait_share = wait_ / (seconds_ * current_);
  steps_ = 0;
  seconds_ = wait_ = 0;
  if (++windows_ == 1) return;  // start-up
  switch (stage_) {
    case Stage::trial:  // back to the base size for one window
      rate_trial_ = rate;
      current_ = base_;
      stage_ = Stage::check;
      return;
    case Stage::check: {
      const bool better = rate_trial_ > kBetter * std::max(rate_before_, rate);
      if (better) {
        current_ = trial_;
        ++changes_;
      }
      if (trial_ > base_)
        retry_after_ = better ? kFirstRetry : std::min(2 * retry_after_, kLastRetry);
      stage_ = Stage::steady;
      windows_since_change_ = 0;
      return;
    }
    case Stage::steady:
      break;
  }
  ++windows_since_change_;
  const auto start_trial = [&](int size) {
    base_ = current_;
    trial_ = size;
    rate_before_ = rate;
    current_ = size;
    stage_ = Stage::trial;
  };
  if (current_ > 1 && wait_share > kWaitShare)
    start_trial(current_ - 1);
  else if (current_ < requested_ && windows_since_change_ >= retry_after_)
    start_trial(current_ + 1);
}

}  // namespace mpsolid
