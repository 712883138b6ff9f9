#include "src/app/thread_governor.hpp"

#include <algorithm>
#include <limits>

namespace mpsolid {

ThreadGovernor::ThreadGovernor(int requested, bool adaptive)
    : requested_(std::max(requested, 1)), current_(requested_), adaptive_(adaptive) {}

void ThreadGovernor::record(std::int64_t steps, double seconds, double wait_seconds) {
  seconds_at_[current_] += seconds;
  if (!adaptive_ || requested_ == 1) return;
  if (seconds > 0) last_rate_ = static_cast<double>(steps) / seconds;
  steps_ += steps;
  seconds_ += seconds;
  wait_ += wait_seconds;
  if (seconds_ >= window_seconds()) end_window();
}

std::int64_t ThreadGovernor::max_batch_steps() const {
  if (!adaptive_ || requested_ == 1) return std::numeric_limits<std::int64_t>::max();
  if (last_rate_ <= 0) return kMinBatch;
  return std::max(kMinBatch, static_cast<std::int64_t>(last_rate_ * window_seconds() / 5));
}

double ThreadGovernor::window_seconds() const {
  if (windows_ == 0) return kStartSeconds;
  return windows_ == 1 || stage_ == Stage::trial ? kTrialSeconds : kWindowSeconds;
}

void ThreadGovernor::resize(int size) {
  if (size != current_) last_rate_ = 0;  // its rate at the new size is not known yet
  current_ = size;
}

void ThreadGovernor::conclude(bool better) {
  if (better) {
    resize(trial_);
    ++changes_;
  }
  // After a success the next trial that way comes soon; after a failure twice as late.
  int& retry = trial_ > base_ ? retry_after_ : retry_down_after_;
  retry = better ? kFirstRetry : std::clamp(2 * retry, kFirstRetry, kLastRetry);
  stage_ = Stage::steady;
  windows_since_change_ = 0;
}

void ThreadGovernor::end_window() {
  const double rate = static_cast<double>(steps_) / seconds_;
  const double wait_share = wait_ / (seconds_ * current_);
  steps_ = 0;
  seconds_ = wait_ = 0;
  if (++windows_ == 1) return;  // start-up
  switch (stage_) {
    case Stage::trial:
      rate_trial_ = rate;
      if (rate_trial_ > kDecisive * rate_before_) {
        conclude(true);
        return;
      }
      resize(base_);  // back to the base size for one window
      stage_ = Stage::check;
      return;
    case Stage::check:
      conclude(rate_trial_ > kBetter * std::max(rate_before_, rate));
      return;
    case Stage::steady:
      break;
  }
  ++windows_since_change_;
  const auto start_trial = [&](int size) {
    base_ = current_;
    trial_ = size;
    rate_before_ = rate;
    resize(size);
    stage_ = Stage::trial;
  };
  // One thread fewer when the threads wait, and now and then anyway: where
  // two threads of one process slow each other down (as on some virtual
  // machines), a team can be slower than a smaller one while hardly waiting.
  if (current_ > 1 && (wait_share > kWaitShare || windows_since_change_ >= retry_down_after_))
    start_trial(current_ - 1);
  else if (current_ < requested_ && windows_since_change_ >= retry_after_)
    start_trial(current_ + 1);
}

}  // namespace mpsolid
