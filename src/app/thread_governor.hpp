#pragma once
// The team size of each batch of steps. A result does not depend on it (the
// same bits at any thread count), so the run may change it: on a machine
// busy with other work, a thread that the OS deschedules holds the team up
// at every barrier, and fewer threads can be faster than more.
//
// It measures windows of about a quarter of a second (the first judged one
// a tenth). After the first judged window, and whenever the threads spent
// more than a fifth of their time waiting, it runs one shorter window (a
// tenth of a second) with one thread fewer, then one more with the current
// size again, and keeps the smaller team only if it beat both neighbouring
// windows by 5 % (the cost of a step drifts as a run goes on: a trial must
// beat the windows on both sides of it), or at once if it ran 1.5x as fast
// as the window before it (no drift does that). A smaller team is tried
// again after 1 s, then after twice as long each time that fails (at most
// 16 s), waiting or not: threads can be slow without waiting (on some
// virtual machines two threads of one process run at half speed each, and
// 2 threads were slower than 1). Below the requested size it tries one
// thread more the same way. The first window, a twentieth of a second, is
// not judged (start-up). So with one other busy process on 2 cores, where 2
// threads ran at about 0.6 of 1 thread's speed, a run spends about 0.15 s
// at 2 threads at the start and a tenth of a second per retry. On an idle
// machine where more threads are faster, the trials cost a few tenths of a
// second of slower running in the first minute, then one a quarter-minute.
// --fixed-threads turns it off.
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

  static constexpr double kWindowSeconds = 0.25;
  static constexpr double kTrialSeconds = 0.1;
  static constexpr double kStartSeconds = 0.05;
  // The length of the window being measured now.
  double window_seconds() const;
  // The most steps the next batch should take: a fifth of the window at the
  // last batch's rate, at least kMinBatch (and just that until a rate at the
  // current size is measured), so that a window ends on time even where the
  // team runs slowly (with two other busy processes on 2 cores, 2 threads
  // took 0.28 s for a batch of 500 steps). No limit when the size is fixed.
  std::int64_t max_batch_steps() const;
  static constexpr std::int64_t kMinBatch = 16;

 private:
  void end_window();
  // Ends a trial: keeps its size if it was better, and sets when to retry.
  void conclude(bool better);
  void resize(int size);

  static constexpr double kWaitShare = 0.2;  // waiting above this: try one thread fewer
  static constexpr double kBetter = 1.05;    // a trial must be this much faster to stay
  static constexpr double kDecisive = 1.5;   // ... or this much faster than the window before it
  static constexpr int kFirstRetry = 4, kLastRetry = 64;  // windows before trying one more

  enum class Stage { steady, trial, check };

  int requested_, current_;
  bool adaptive_;
  double last_rate_ = 0;  // steps per second of the last batch
  // The window being measured.
  std::int64_t steps_ = 0;
  double seconds_ = 0, wait_ = 0;
  int windows_ = 0;
  // A trial: the size tried, the rate before it and its own rate.
  Stage stage_ = Stage::steady;
  int base_ = 0, trial_ = 0;
  double rate_before_ = 0, rate_trial_ = 0;
  int windows_since_change_ = 0;
  int retry_after_ = kFirstRetry;
  int retry_down_after_ = 1;  // windows before trying one thread fewer anyway
  int changes_ = 0;
  std::map<int, double> seconds_at_;
};

}  // namespace mpsolid
