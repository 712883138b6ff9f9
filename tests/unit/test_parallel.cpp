// The team's loops (src/core/parallel.hpp): every index exactly once, the
// chunks of a thread that is held up taken by the others, and the time
// threads wait at barriers counted.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <vector>

#include "src/core/parallel.hpp"

namespace mpsolid {
namespace {

constexpr std::size_t kNone = static_cast<std::size_t>(-1);

// Which thread ran each index of `n`, over `loops` consecutive team loops;
// rank 1 sleeps `delay` before each loop.
std::vector<std::vector<std::size_t>> owners(int threads, std::size_t n, int loops,
                                             std::chrono::milliseconds delay) {
  set_thread_count(threads);
  std::vector<std::vector<std::size_t>> ran(static_cast<std::size_t>(loops),
                                            std::vector<std::size_t>(n, kNone));
  run_in_team([&] {
    for (auto& loop : ran) {
      if (team_rank() == 1) std::this_thread::sleep_for(delay);
      const std::size_t rank = team_rank();
      parallel_blocks(0, n, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) {
          EXPECT_EQ(loop[i], kNone) << "index " << i << " ran twice";
          loop[i] = rank;
        }
      });
    }
  });
  set_thread_count(1);
  return ran;
}

TEST(TeamLoops, EveryIndexRunsOnce) {
  for (int threads : {2, 3, 4})
    for (const auto& loop : owners(threads, 5000, 6, std::chrono::milliseconds(0)))
      for (std::size_t i = 0; i < loop.size(); ++i) ASSERT_NE(loop[i], kNone) << i;
}

TEST(TeamLoops, AHeldUpThreadsChunksAreTakenByTheOthers) {
  const auto ran = owners(2, 5000, 3, std::chrono::milliseconds(30));
  const Range second = static_block(0, 5000, 1, 2);
  for (const auto& loop : ran) {
    std::size_t taken = 0;
    for (std::size_t i = second.begin; i < second.end; ++i) taken += loop[i] == 0;
    // Rank 1 sleeps 30 ms while rank 0 has microseconds of work: rank 0
    // takes all of rank 1's chunks but the ones rank 1 claims on waking.
    EXPECT_GT(taken, second.size() / 2);
  }
}

// Teams started by two threads of a program (two simulations side by side)
// have their own barrier and chunk counters.
TEST(TeamLoops, TeamsOfTwoProgramThreadsDoNotMix) {
  constexpr std::size_t n = 3000;
  std::vector<std::vector<int>> hits(2, std::vector<int>(n, 0));
  std::vector<std::thread> starters;
  for (std::size_t t = 0; t < 2; ++t)
    starters.emplace_back([&, t] {
      set_thread_count(2);
      run_in_team([&] {
        for (int loop = 0; loop < 200; ++loop)
          parallel_blocks(0, n, [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) ++hits[t][i];
          });
      });
    });
  for (auto& s : starters) s.join();
  for (const auto& h : hits)
    for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(h[i], 200) << i;
}

TEST(TeamLoops, TimeWaitingAtBarriersIsCounted) {
  set_thread_count(2);
  const double before = team_wait_seconds();
  run_in_team([&] {
    if (team_rank() == 1) std::this_thread::sleep_for(std::chrono::milliseconds(40));
    parallel_blocks(0, 10, [](std::size_t, std::size_t) {});
  });
  set_thread_count(1);
  // Rank 0 waited for rank 1 at the loop's barrier.
  EXPECT_GE(team_wait_seconds() - before, 0.035);
}

}  // namespace
}  // namespace mpsolid
