// Mass-proportional damping (src/core/damping.hpp): a block translating
// freely slows by the scheme's factor each step and the energy it loses is
// the damping's loss exactly; the window starts and stops where the case
// says; the rod's energy balance closes with the loss counted; same bits at
// 1-4 threads and across a checkpoint inside the window.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

const char* kWindow = "\n[damping]\ncoefficient = 2.0e4\nstart = 1.0e-5\nend = 3.0e-5\n";

CaseSpec sliding_block() {
  return load_case_text(testing::rubber_case_head("sliding", "paper") +
                            "[bodies.block]\nkind = \"elastic\"\nmaterial = \"rubber\"\nx = "
                            "[0.0, 0.006]\ny = [0.0, 0.004]\nvelocity = [3.0, -4.0]\n"
                            "[time]\ndt = 1e-7\nend = 1e-4\n" +
                            kWindow,
                        "sliding.toml");
}

TEST(Damping, AFreeBlockSlowsByTheSchemesFactorAndLosesItsEnergyToTheDamping) {
  Simulation sim(sliding_block());
  const double ke0 = sim.diagnostics().kinetic_energy;
  sim.advance(100);  // up to the window: no damping yet
  EXPECT_NEAR(sim.particles().vx[0], 3.0, 1e-12);
  EXPECT_EQ(sim.diagnostics().damping_loss, 0.0);
  sim.advance(200);  // the window: 200 steps
  const double c = 2.0e4, dt = 1e-7;
  const double factor = std::pow((1 - 0.5 * c * dt) / (1 + 0.5 * c * dt), 200);
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    EXPECT_NEAR(sim.particles().vx[i], 3.0 * factor, 1e-12);
    EXPECT_NEAR(sim.particles().vy[i], -4.0 * factor, 1e-12);
  }
  const Diagnostics d = sim.diagnostics();
  EXPECT_NEAR(d.kinetic_energy + d.damping_loss, ke0, 1e-12 * ke0);
  EXPECT_GT(d.damping_loss, 0.5 * ke0);  // v^2 down by exp(-0.8)
  const double vx = sim.particles().vx[0];
  sim.advance(100);  // after the window
  EXPECT_NEAR(sim.particles().vx[0], vx, 1e-12);
  EXPECT_EQ(sim.diagnostics().damping_loss, d.damping_loss);
}

CaseSpec damped_rod(const std::vector<std::string>& overrides = {}) {
  std::string text = testing::rod_case().resolved_toml;
  return load_case_text(text + kWindow, "damped_rod.toml", overrides);
}

TEST(Damping, TheRodsEnergyBalanceClosesWithTheLoss) {
  Simulation sim(damped_rod());
  sim.advance(5000);
  const Diagnostics d = sim.diagnostics();
  EXPECT_GT(d.damping_loss, 0.1 * d.external_work);
  EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy + d.damping_loss - d.external_work),
            0.01 * d.external_work);
}

// The state arrays (the forces of a damped step are the damped ones, which
// a refresh of the fields recomputes without the damping).
bool same_state(const ParticleStore& a, const ParticleStore& b) {
  for (const StateArray& array : state_arrays(a.dimension))
    if (std::memcmp((a.*array.member).data(), (b.*array.member).data(),
                    a.size() * sizeof(double)) != 0)
      return false;
  return a.size() == b.size();
}

TEST(Damping, SameBitsAt1To4ThreadsAndAcrossACheckpoint) {
  set_thread_count(1);
  Simulation one(damped_rod({"l0=0.001"}));
  one.advance(2000);
  for (const int threads : {2, 3, 4}) {
    set_thread_count(threads);
    Simulation many(damped_rod({"l0=0.001"}));
    many.advance(1500);
    Simulation straight(damped_rod({"l0=0.001"}));
    straight.advance(2000);
    EXPECT_TRUE(same_state(one.state().particles, straight.state().particles)) << threads;
    SolverState copy = many.state();
    Simulation resumed(damped_rod({"l0=0.001"}));
    resumed.state_to_change() = copy;  // as a checkpoint restores it, inside the window
    resumed.advance(500);
    EXPECT_TRUE(same_state(one.state().particles, resumed.state().particles)) << threads;
    EXPECT_EQ(one.diagnostics().damping_loss, resumed.diagnostics().damping_loss);
  }
  set_thread_count(available_cores());
}

}  // namespace
}  // namespace mpsolid
