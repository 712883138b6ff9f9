// Prescribed motion (src/core/rigid_body.hpp): driven rigid bodies follow
// their velocity history exactly whatever pushes on them, their drivers'
// work closes the energy balance, and a wall given a motion is such a body.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

CaseSpec grips(const std::vector<std::string>& overrides = {}) {
  return load_case(testing::source_path("cases/holed_plate_grips.toml"), overrides);
}

TEST(PrescribedMotion, GripsFollowTheirHistoryExactly) {
  Simulation sim(grips({"l0=0.001"}));
  const double dt = sim.spec().dt;
  const std::int64_t steps = 600;  // through the ramp (1 ms) and past it
  ASSERT_GT(static_cast<double>(steps) * dt, 1.2e-3);
  sim.advance(steps);
  const RigidBody& left = sim.state().rigid_bodies.at(0);
  const RigidBody& right = sim.state().rigid_bodies.at(1);
  ASSERT_EQ(left.name, "left_grip");
  double x = 0, v = 0;
  for (std::int64_t k = 0; k < steps; ++k) {
    v = left.motion.factor(static_cast<double>(k) * dt, dt) * -0.5;
    x += dt * v;
  }
  EXPECT_NEAR(left.xg - left.xg0, x, 1e-13);  // xg += dt v rounds at 0.03 m
  EXPECT_EQ(left.vx, v);
  EXPECT_EQ(left.vx, -0.5);
  EXPECT_EQ(left.vy, 0.0);
  EXPECT_EQ(left.omega, 0.0);
  EXPECT_NEAR(right.xg - right.xg0, -x, 1e-13);
  // The drivers did the work that stretched the plate.
  const Diagnostics d = sim.diagnostics();
  EXPECT_GT(left.work, 0.0);
  EXPECT_NEAR(left.work, right.work, 1e-9 * left.work);
  EXPECT_NEAR(d.external_work, left.work + right.work, 1e-12 * d.external_work);
  EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy - d.external_work), 0.01 * d.external_work);
}

// The rod pushed by its plate driven at 1 m/s, the plate's load then doing
// work against the driver: the balance still closes, the plate never slows.
TEST(PrescribedMotion, ADrivenPlateIgnoresItsLoadAndTheBalanceCloses) {
  const std::string text =
      testing::rod_case().resolved_toml + "\n[bodies.plate.motion]\nvelocity = [1.0, 0.0]\n";
  Simulation sim(load_case_text(text, "piston.toml"));
  sim.advance(3000);
  const RigidBody& plate = sim.state().rigid_bodies.at(0);
  EXPECT_EQ(plate.vx, 1.0);
  EXPECT_NEAR(plate.xg - plate.xg0, 3000 * 1e-8, 1e-13);
  const Diagnostics d = sim.diagnostics();
  EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy - d.external_work), 0.01 * d.external_work);
}

TEST(PrescribedMotion, AWallGivenAMotionMovesAsARigidBody) {
  const std::string text = testing::rod_case().resolved_toml +
                           "\n[bodies.wall.motion]\nvelocity = [-1.0, 0.0]\nstart = 1e-6\n";
  Simulation sim(load_case_text(text, "anvil.toml"));
  ASSERT_EQ(sim.state().rigid_bodies.size(), 2u);
  sim.advance(300);
  const RigidBody& wall = sim.state().rigid_bodies.at(1);
  EXPECT_EQ(wall.name, "wall");
  EXPECT_NEAR(wall.xg - wall.xg0, -200 * 1e-8, 1e-13);  // from step 100 on
}

TEST(PrescribedMotion, SameBitsAt1To4Threads) {
  set_thread_count(1);
  Simulation one(grips({"l0=0.001"}));
  one.advance(500);
  for (const int threads : {2, 3, 4}) {
    set_thread_count(threads);
    Simulation many(grips({"l0=0.001"}));
    many.advance(500);
    EXPECT_TRUE(testing::same_bits(one.state().particles, many.state().particles)) << threads;
    EXPECT_EQ(one.state().rigid_bodies[0].work, many.state().rigid_bodies[0].work);
  }
  set_thread_count(available_cores());
}

}  // namespace
}  // namespace mpsolid
