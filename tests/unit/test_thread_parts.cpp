// The threads as ranks (src/solver/thread_parts.hpp, src/distributed/
// thread_ranks.hpp): the mailboxes deliver every message of many calls in
// a row to the right thread, and any cut of the state over any thread count
// steps to the bits of one thread, for every model, with contact, across
// cuts made mid-run.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/thread_parts.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

// Three threads, each calling every kind of call many times in a row (the
// letters alternate by parity, so a slow reader must never see a letter
// overwritten): each gets exactly what the others sent it in that call.
TEST(ThreadRanks, EveryCallDeliversItsOwnLetters) {
  constexpr int kThreads = 3, kCalls = 2000;
  set_thread_count(kThreads);
  ThreadMailboxes boxes(kThreads);
  std::vector<int> failures(kThreads, 0);
  run_in_team([&] {
    ASSERT_EQ(team_size(), static_cast<std::size_t>(kThreads));
    const int me = static_cast<int>(team_rank());
    ThreadRanks ranks(boxes, me);
    int& failed = failures[static_cast<std::size_t>(me)];
    for (int call = 0; call < kCalls; ++call) {
      // A ring: each thread sends call + 10 * me (and a length that varies
      // with the call) to both neighbours.
      const int left = (me + kThreads - 1) % kThreads, right = (me + 1) % kThreads;
      const std::size_t length = 1 + static_cast<std::size_t>(call % 5);
      const std::vector<int> peers{left, right};
      std::vector<std::vector<double>> out(2, std::vector<double>(length, call + 10.0 * me)),
          in(2, std::vector<double>(length, -1.0));
      ranks.exchange(peers, out, in);
      for (std::size_t k = 0; k < 2; ++k)
        for (const double v : in[k]) failed += v != call + 10.0 * peers[k];
      const std::vector<double> all = ranks.all_gather({static_cast<double>(me * call)});
      for (int r = 0; r < kThreads; ++r) failed += all.at(static_cast<std::size_t>(r)) != r * call;
      failed += ranks.max(call * (me + 1)) != call * kThreads;
    }
  });
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(failures[static_cast<std::size_t>(t)], 0) << t;
  set_thread_count(available_cores());
}

// `steps` steps at one thread (the whole state, the team step).
SolverState stepped_state_alone(const CaseSpec& spec, std::int64_t steps) {
  set_thread_count(1);
  Simulation sim(spec);
  sim.advance(steps);
  return sim.state();
}
ParticleStore stepped_alone(const CaseSpec& spec, std::int64_t steps) {
  return stepped_state_alone(spec, steps).particles;
}

// The same steps on `threads` threads as ranks, cut again after each third
// of them: at the first cut shifted by `shift` particles, then back.
SolverState stepped_state_in_parts(const CaseSpec& spec, int threads, std::int64_t steps,
                                   std::size_t shift) {
  set_thread_count(1);
  Simulation sim(spec);
  SolverState& state = sim.state_to_change();
  set_thread_count(threads);
  ThreadParts parts(sim.spec(), state, threads);  // its time step chosen ("auto")
  const Decomposition first = parts.decomposition();
  Decomposition shifted = first;
  for (std::size_t r = 1; r + 1 < shifted.starts.size(); ++r)
    shifted.starts[r] = std::min(shifted.starts[r] + shift, state.particles.size());
  PhaseTimers timers;
  const std::int64_t third = steps / 3;
  EXPECT_TRUE(parts.advance(state, third, false, timers));
  parts.cut_again(state, shifted);

  EXPECT_TRUE(parts.advance(state, third, false, timers));
  parts.cut_again(state, first);
  EXPECT_TRUE(parts.advance(state, steps - 2 * third, false, timers));
  parts.bring_back(state);
  set_thread_count(available_cores());
  EXPECT_EQ(state.step, steps);
  return state;
}
ParticleStore stepped_in_parts(const CaseSpec& spec, int threads, std::int64_t steps,
                               std::size_t shift) {
  return stepped_state_in_parts(spec, threads, steps, shift).particles;
}

TEST(ThreadParts, AnyCutAtAnyThreadCountGivesTheBitsOfOneThreadForEveryModel) {
  for (const std::string& model : model_names()) {
    SCOPED_TRACE(model);
    const CaseSpec spec = testing::rod_case({"l0=0.002", "model=" + model});
    const ParticleStore alone = stepped_alone(spec, 300);
    for (int threads : {2, 3, 4})
      for (std::size_t shift : {std::size_t{7}, std::size_t{61}})
        EXPECT_TRUE(testing::same_bits(alone, stepped_in_parts(spec, threads, 300, shift)))
            << threads << " threads, cut shifted by " << shift;
  }
}

// A body under a pressure is cut like any other: each part positions the
// nodes it hosts, the parts share them, and every part has the load's
// running step (its factor, node positions and work) bit for bit.
TEST(ThreadParts, APressuresBodyCutBetweenThreadsGivesTheBitsOfOneThread) {
  for (const std::string file : {"cases/disk_blast.toml", "cases/ring_pressure.toml"}) {
    SCOPED_TRACE(file);
    const CaseSpec spec = load_case(testing::source_path(file));
    const SolverState alone = stepped_state_alone(spec, 150);
    for (const auto& [threads, shift] :
         {std::pair{2, std::size_t{7}}, std::pair{3, std::size_t{200}},
          std::pair{4, std::size_t{61}}}) {
      const SolverState parts = stepped_state_in_parts(spec, threads, 150, shift);
      EXPECT_TRUE(testing::same_bits(alone.particles, parts.particles))
          << threads << " threads, cut shifted by " << shift;
      for (std::size_t l = 0; l < alone.loads.size(); ++l) {
        const StepLoad &a = alone.loads[l], &b = parts.loads[l];
        EXPECT_EQ(a.work, b.work);
        EXPECT_EQ(a.factor, b.factor);
        EXPECT_EQ(a.surface.x, b.surface.x);
        EXPECT_EQ(a.surface.target_fy, b.surface.target_fy);
        EXPECT_EQ(load_work(alone.particles, a), load_work(parts.particles, b));
      }
    }
  }
}

TEST(ThreadParts, ContactGivesTheBitsOfOneThread) {
  // Past the first touch (at about 1 ms), with the Verlet list rebuilt.
  const CaseSpec spec = load_case(testing::source_path("cases/colliding_blocks.toml"));
  const auto steps = static_cast<std::int64_t>(0.0016 / spec.dt);
  const ParticleStore alone = stepped_alone(spec, steps);
  for (int threads : {2, 3})
    EXPECT_TRUE(testing::same_bits(alone, stepped_in_parts(spec, threads, steps, 13)))
        << threads << " threads";
}

}  // namespace
}  // namespace mpsolid
