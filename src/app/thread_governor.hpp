#pragma once
// The team size of each batch of steps. A result does not depend on it (the
// same bits at any thread count), so the run may change it: on a machine
// busy with other work, a thread that the OS deschedules holds the team up
// at every barrier, and fewer threads can be faster than more. When the
// threads spend more than a fifth of their time waiting (over a window of
// about a second), the governor measures one thread fewer for a window and
// keeps whichever ran more steps per second; below the requested size it
// tries one more every ten windows. On an idle machine the threads hardly
// wait and the requested size is kept. --fixed-threads turns it off.
#include <cstdint>
#include <map>

namespace mpsolid {

class ThreadGovernor {
 public:
  ThreadGovernor(int requested, bool adaptive);

  // The team size for the next batch.
  int threads() const { return current_; }
  // After each batch: its steps, wall seconds and the threads' summed wait.
  void record(std::int64_t steps, double seconds, double wait_seconds);

  // Wall seconds run at each team size, and how often it changed.
  const std::map<int, double>& seconds_at() const { return seconds_at_; }
  int changes() const { return changes_; }

 private:
  void end_window();

  static constexpr double kWindowSeconds = 0.25;
  static constexpr double kWaitShare = 0.2;  // waiting above this: try one thread fewer
  static constexpr int kWindowsBeforeRetry = 40;
  static constexpr double kBetter = 1.05;  // a trial must be this much faster to stay

  int requested_, current_;
  bool adaptive_;
  // The window being measured.
  std::int64_t steps_ = 0;
  double seconds_ = 0, wait_ = 0;
  // A trial: the size it left and that size's rate; 0 when none.
  int trial_from_ = 0;
  double rate_before_ = 0;
  int windows_since_change_ = 0;
  int changes_ = 0;
  std::map<int, double> seconds_at_;
};

}  // namespace mpsolid
