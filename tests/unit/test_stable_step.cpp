// time.dt = "auto": the estimate of the symplectic-Euler stability limit
// 2 / omega_max from power iteration on each model's own force pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "src/core/parallel.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/time_step_choice.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using testing::free_block_case;
using testing::rod_case;

const char* const kModels[] = {"paper", "paper_conservative", "finite_strain", "linear_elastic"};

double limit_of(const CaseSpec& spec) {
  Simulation sim(spec);
  EXPECT_TRUE(sim.stable_step().converged);
  return sim.stable_step().dt_limit;
}

TEST(StableStep, PaperModelMatchesTheIndependentLimitOnTheRod) {
  // Independent checks put the paper model's limit on the rod at 11.9 us
  // (l0 = 2 mm) and 5.9 us (l0 = 1 mm).
  const double coarse = limit_of(rod_case({"time.dt=\"auto\"", "time.end=1e-4"}));
  const double fine = limit_of(rod_case({"time.dt=\"auto\"", "time.end=1e-4", "l0=0.001"}));
  EXPECT_NEAR(coarse, 11.9e-6, 0.012 * 11.9e-6);
  EXPECT_NEAR(fine, 5.9e-6, 0.012 * 5.9e-6);
  // The limit is l0 / (a wave speed): halving l0 halves it.
  EXPECT_NEAR(fine / coarse, 0.5, 0.005);
}

TEST(StableStep, ChosenStepIsSafetyTimesLimitWithWholeStepsPerOutput) {
  Simulation sim(rod_case(
      {"time.dt=\"auto\"", "time.safety=0.25", "time.end=1e-4", "output.frame_interval=1e-4"}));
  const double dt = sim.spec().dt;
  EXPECT_LE(dt, 0.25 * sim.stable_step().dt_limit);
  EXPECT_GT(dt, 0.24 * sim.stable_step().dt_limit);
  EXPECT_DOUBLE_EQ(1e-4 / dt, std::round(1e-4 / dt));
  EXPECT_EQ(sim.spec().dt, dt);
}

TEST(StableStep, SameStepAtAnyThreadCount) {
  set_thread_count(1);
  const double one = limit_of(rod_case({"time.dt=\"auto\"", "time.end=1e-4"}));
  set_thread_count(2);
  const double two = limit_of(rod_case({"time.dt=\"auto\"", "time.end=1e-4"}));
  set_thread_count(1);
  EXPECT_EQ(one, two);
}

// The estimate on every rank's part of `global` (threads as ranks), which
// must agree on every rank.
StableStepEstimate estimate_in_parts(const CaseSpec& spec, const SolverState& global, int ranks) {
  set_thread_count(ranks);
  ThreadMailboxes boxes(ranks);
  std::vector<StableStepEstimate> got(static_cast<std::size_t>(ranks));
  run_in_team([&] {
    EXPECT_EQ(team_size(), static_cast<std::size_t>(ranks));
    const auto me = static_cast<int>(team_rank());
    serial_section([&] {
      ThreadRanks world(boxes, me);
      RankPart part = make_rank_part(spec, global, world);
      got[static_cast<std::size_t>(me)] = estimate_part_stable_step(spec, part, world);
    });
  });
  set_thread_count(1);
  for (const StableStepEstimate& e : got) {
    EXPECT_EQ(e.omega_max, got[0].omega_max);
    EXPECT_EQ(e.iterations, got[0].iterations);
  }
  return got[0];
}

TEST(StableStep, SameBitsOnEveryRankCountsParts) {
  // Every model in the plane (rotations or none), a wall and rigid bodies,
  // contact's bound, and space.
  std::vector<CaseSpec> cases;
  for (const char* model : kModels)
    cases.push_back(rod_case(
        {"time.dt=\"auto\"", "time.end=1e-4", "l0=0.004", std::string("model=\"") + model + "\""}));
  for (const char* file :
       {"cases/colliding_blocks.toml", "cases/disk_impact.toml", "cases/spinning_cube.toml"})
    cases.push_back(load_case(testing::source_path(file), {}));
  for (const CaseSpec& spec : cases) {
    SCOPED_TRACE(spec.name + " " + spec.model);
    set_thread_count(1);
    Simulation sim(spec);
    const SolverState& global = sim.state();
    const StableStepEstimate whole = estimate_case_stable_step(sim.spec(), global);
    ASSERT_GT(whole.dt_limit, 0.0);
    // The run's own estimate is this one.
    EXPECT_EQ(whole.omega_max, sim.stable_step().omega_max);
    for (const int ranks : {2, 3, 4}) {
      const StableStepEstimate parts = estimate_in_parts(sim.spec(), global, ranks);
      EXPECT_EQ(parts.omega_max, whole.omega_max) << ranks << " ranks";
      EXPECT_EQ(parts.dt_limit, whole.dt_limit) << ranks << " ranks";
      EXPECT_EQ(parts.iterations, whole.iterations) << ranks << " ranks";
      EXPECT_EQ(parts.converged, whole.converged) << ranks << " ranks";
    }
  }
  set_thread_count(available_cores());
}

// Runs a free block from a tiny checkerboard kick at `fraction` of the
// estimated limit and returns the largest speed after `steps`.
double speed_after(const std::string& model, double fraction, int steps) {
  CaseSpec spec = free_block_case(12, 8, false, 1e-7, model);
  const double limit = [&] {
    CaseSpec a = spec;
    a.dt_auto = true;
    a.dt = 0;
    return Simulation(a).stable_step().dt_limit;
  }();
  spec.dt = fraction * limit;
  Simulation sim(spec);
  ParticleStore& p = sim.state_to_change().particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double sign = ((static_cast<long>(std::floor(p.x0[i] / 1e-3)) +
                          static_cast<long>(std::floor(p.y0[i] / 1e-3))) &
                         1)
                            ? -1.0
                            : 1.0;
    p.vx[i] = 1e-6 * sign;
    p.vy[i] = -1e-6 * sign;
  }
  sim.advance(steps);
  double fastest = 0;  // a blown-up run counts as infinitely fast
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double v = std::hypot(p.vx[i], p.vy[i]);
    fastest = std::isfinite(v) ? std::max(fastest, v) : INFINITY;
  }
  return fastest;
}

TEST(StableStep, EstimateSeparatesStableFromUnstableSteps) {
  // Just below the estimated limit a kick of 1 um/s stays that small; just
  // above it the stiffest mode grows by more than 1e6 in 100 steps (and
  // overflows soon after, so the count stays short).
  for (const char* model : kModels) {
    SCOPED_TRACE(model);
    EXPECT_LT(speed_after(model, 0.97, 400), 1e-4);
    EXPECT_LT(speed_after(model, 0.97, 100), 1e-4);
    EXPECT_GT(speed_after(model, 1.03, 100), 1.0);
  }
}

}  // namespace
}  // namespace mpsolid
