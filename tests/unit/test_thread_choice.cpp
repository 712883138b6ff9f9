// The thread count of a run: --threads, else OMP_NUM_THREADS, else every
// core; a bad OMP_NUM_THREADS is bad input; more threads than cores warn.
// The governor that gives up threads that only wait on a busy machine.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include <cstdlib>

#include "src/app/thread_choice.hpp"
#include "src/app/thread_governor.hpp"
#include "src/core/types.hpp"

namespace mpsolid {
namespace {

class Environment {
 public:
  explicit Environment(const char* value) {
    if (const char* old = std::getenv("OMP_NUM_THREADS")) saved_ = old;
    if (value)
      ::setenv("OMP_NUM_THREADS", value, 1);
    else
      ::unsetenv("OMP_NUM_THREADS");
  }
  ~Environment() {
    if (saved_.empty())
      ::unsetenv("OMP_NUM_THREADS");
    else
      ::setenv("OMP_NUM_THREADS", saved_.c_str(), 1);
  }

 private:
  std::string saved_;
};

TEST(ThreadChoice, FlagThenEnvironmentThenCores) {
  {
    Environment env("3");
    EXPECT_EQ(choose_threads(2, 8).threads, 2);
    EXPECT_EQ(choose_threads(2, 8).source, "--threads");
    EXPECT_EQ(choose_threads(0, 8).threads, 3);
    EXPECT_EQ(choose_threads(0, 8).source, "OMP_NUM_THREADS");
  }
  {
    Environment env("4,2");  // nested levels: the first is ours
    EXPECT_EQ(choose_threads(0, 8).threads, 4);
  }
  {
    Environment env(nullptr);
    EXPECT_EQ(choose_threads(0, 8).threads, 8);
    EXPECT_EQ(choose_threads(0, 8).source, "all cores");
  }
}

TEST(ThreadChoice, BadEnvironmentIsBadInput) {
  for (const char* bad : {"abc", "0", "-2", "3x", "2.5"}) {
    Environment env(bad);
    EXPECT_THROW(choose_threads(0, 4), InputError) << bad;
    EXPECT_NO_THROW(choose_threads(1, 4)) << "--threads wins over " << bad;
  }
}

TEST(ThreadChoice, MoreThreadsThanCoresWarn) {
  Environment env(nullptr);
  EXPECT_TRUE(choose_threads(2, 2).warning.empty());
  const ThreadChoice many = choose_threads(5, 2);
  EXPECT_EQ(many.threads, 5);
  EXPECT_NE(many.warning.find("5 threads"), std::string::npos) << many.warning;
  EXPECT_NE(many.warning.find("2 cores"), std::string::npos) << many.warning;
}

// Feeds the governor one measuring window at its current size: `rate`
// steps per second, the threads waiting `wait_share` of their time.
void window(ThreadGovernor& g, double rate, double wait_share) {
  const double dt = g.window_seconds() / 5;
  for (int k = 0; k < 5; ++k)
    g.record(static_cast<std::int64_t>(rate * dt), dt * 1.0000001, wait_share * dt * g.threads());
}

TEST(ThreadGovernor, KeepsTheRequestedSizeWhileThreadsHardlyWait) {
  ThreadGovernor g(2, true);
  for (int k = 0; k < 100; ++k) window(g, 1000, 0.05);
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.changes(), 0);
}

TEST(ThreadGovernor, DropsAThreadThatOnlyWaitsAndTriesItAgainLater) {
  ThreadGovernor g(2, true);
  window(g, 1000, 0.4);  // start-up: not judged
  EXPECT_EQ(g.threads(), 2);
  window(g, 1000, 0.4);  // waiting: try 1 thread
  EXPECT_EQ(g.threads(), 1);
  window(g, 1300, 0.0);  // the trial, 1.3x faster; then 2 threads again for one window
  EXPECT_EQ(g.threads(), 2);
  window(g, 1000, 0.4);  // the trial beat both sides: kept
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.changes(), 1);
  // Tries 2 threads again after 4 windows; they are still slower, so the
  // next try waits twice as long.
  int windows = 0;
  while (g.threads() == 1 && windows < 100) {
    window(g, 1800, 0.0);
    ++windows;
  }
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(windows, 4);
  window(g, 1000, 0.4);  // the trial at 2: slower
  window(g, 1800, 0.0);  // back at 1 for the check
  EXPECT_EQ(g.threads(), 1);
  windows = 0;
  while (g.threads() == 1 && windows < 100) {
    window(g, 1800, 0.0);
    ++windows;
  }
  EXPECT_EQ(windows, 8);
}

TEST(ThreadGovernor, ADecisiveTrialIsKeptAtOnceInShortWindows) {
  ThreadGovernor g(2, true);
  EXPECT_EQ(g.window_seconds(), ThreadGovernor::kStartSeconds);
  window(g, 1000, 0.4);                                          // start-up
  EXPECT_EQ(g.window_seconds(), ThreadGovernor::kTrialSeconds);  // the first judged one: short
  window(g, 1000, 0.4);  // waiting: try 1 thread, in a short window
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.window_seconds(), ThreadGovernor::kTrialSeconds);
  // The rate at 1 thread is not known yet: a short first batch.
  EXPECT_EQ(g.max_batch_steps(), ThreadGovernor::kMinBatch);
  window(g, 2000, 0.0);  // twice as fast: kept without a check window
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.changes(), 1);
  EXPECT_EQ(g.window_seconds(), ThreadGovernor::kWindowSeconds);
  // Seconds at 2 threads: the start-up and the judged window only.
  EXPECT_NEAR(g.seconds_at().at(2),
              1.0000001 * (ThreadGovernor::kStartSeconds + ThreadGovernor::kTrialSeconds), 1e-9);
}

TEST(ThreadGovernor, BatchesFitAFifthOfTheWindowAtTheLastRate) {
  ThreadGovernor g(2, true);
  EXPECT_EQ(g.max_batch_steps(), ThreadGovernor::kMinBatch);
  g.record(16, 0.004, 0.0);  // 4000 steps/s in the start-up window (0.05 s)
  EXPECT_EQ(g.max_batch_steps(), 40);
  g.record(2300, 0.046, 0.0);  // 50,000 steps/s, ending the start-up; the next window is 0.1 s
  EXPECT_EQ(g.max_batch_steps(), 1000);
  g.record(5000, 0.1, 0.0);  // ends the first judged window: a trial at 1 thread, rate unknown
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.max_batch_steps(), ThreadGovernor::kMinBatch);
  g.record(2000, 0.1, 0.0);  // the trial, slower: 2 threads again, rate unknown again
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.max_batch_steps(), ThreadGovernor::kMinBatch);
  g.record(12500, 0.25, 0.0);  // 50,000 steps/s; windows of 0.25 s from now on
  EXPECT_EQ(g.max_batch_steps(), 2500);
  g.record(1, 1.0, 0.0);  // very slow: never below the minimum
  EXPECT_EQ(g.max_batch_steps(), ThreadGovernor::kMinBatch);
  ThreadGovernor fixed(2, false), one(1, true);
  EXPECT_EQ(fixed.max_batch_steps(), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(one.max_batch_steps(), std::numeric_limits<std::int64_t>::max());
}

// Two threads slower than one while hardly waiting (seen on a virtual
// machine): the trial after the first judged window finds it.
TEST(ThreadGovernor, DropsASlowerTeamWhoseThreadsHardlyWait) {
  ThreadGovernor g(2, true);
  window(g, 1000, 0.05);  // start-up
  window(g, 1000, 0.05);  // hardly waiting, but try 1 thread once
  EXPECT_EQ(g.threads(), 1);
  window(g, 1750, 0.0);  // 1.75x as fast: kept at once
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.changes(), 1);
}

// Where more threads are faster, the trials of fewer come ever more rarely.
TEST(ThreadGovernor, TriesFewerThreadsLessAndLessOftenWhileThatIsSlower) {
  ThreadGovernor g(2, true);
  window(g, 1000, 0.05);  // start-up
  std::vector<int> trials;
  for (int k = 1; k < 200; ++k) {
    window(g, g.threads() == 2 ? 1000 : 600, 0.05);
    if (g.threads() == 1) trials.push_back(k);
  }
  EXPECT_EQ(g.changes(), 0);
  // After windows 1, then 4, 8, 16, 32, 64 windows of 2 threads later (each
  // trial and its check window count as two more).
  EXPECT_EQ(trials, (std::vector<int>{1, 7, 17, 35, 69, 135}));
}

TEST(ThreadGovernor, ATrialMustBeatTheWindowsOnBothSides) {
  ThreadGovernor g(2, true);
  window(g, 1000, 0.4);
  window(g, 1000, 0.4);  // try 1 thread
  window(g, 1300, 0.0);  // the trial: faster than before it ...
  window(g, 1400, 0.3);  // ... but not than after it (the run got cheaper)
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.changes(), 0);
}

TEST(ThreadGovernor, FixedThreadsNeverChange) {
  ThreadGovernor g(2, false);
  for (int k = 0; k < 20; ++k) window(g, 1000, 0.9);
  EXPECT_EQ(g.threads(), 2);
  EXPECT_EQ(g.seconds_at().size(), 1u);
}

}  // namespace
}  // namespace mpsolid
