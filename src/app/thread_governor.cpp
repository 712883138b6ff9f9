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
  ++windows_since_change_;
  if (trial_from_ != 0) {  // a trial window ends: keep the faster size
    if (!(rate > kBetter * rate_before_)) current_ = trial_from_;
    changes_ += current_ != trial_from_;
    trial_from_ = 0;
    windows_since_change_ = 0;
    return;
  }
  const auto start_trial = [&](int size) {
    trial_from_ = current_;
    rate_before_ = rate;
    current_ = size;
  };
  if (current_ > 1 && wait_share > kWaitShare)
    start_trial(current_ - 1);
  else if (current_ < requested_ && windows_since_change_ >= kWindowsBeforeRetry)
    start_trial(current_ + 1);
}

}  // namespace mpsolid
