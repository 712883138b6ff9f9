// Each blow-up check fires on the state it is meant to catch, names the right
// particle, and stays quiet on a healthy state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "src/core/stability.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(Stability, HealthyStatePassesEveryCheck) {
  for (const std::string model :
       {"paper", "paper_conservative", "finite_strain", "linear_elastic"}) {
    Simulation sim(testing::rod_case({"model=" + model}));
    sim.advance(500);
    Diagnostics d;
    const StabilityVerdict v = sim.check_stability(&d);
    EXPECT_TRUE(v.ok) << model << ": " << v.criterion;
    EXPECT_GT(d.external_work, 0.0);
  }
}

TEST(Stability, NonFiniteValueIsFoundAtItsParticle) {
  Simulation sim(testing::rod_case());
  sim.state_to_change().particles.vx[137] = std::numeric_limits<double>::quiet_NaN();
  const StabilityVerdict v = sim.check_stability();
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.particle, 137u);
  EXPECT_NE(v.criterion.find("non-finite"), std::string::npos);
}

TEST(Stability, SpeedAboveTheDilatationalWaveSpeed) {
  Simulation sim(testing::rod_case());
  const std::size_t i = sim.particles().elastic.begin + 42;
  sim.state_to_change().particles.vx[i] = 320.0;  // rubber: c_d = 306 m/s
  const StabilityVerdict v = sim.check_stability();
  EXPECT_FALSE(v.ok);
  EXPECT_EQ(v.particle, i);
  EXPECT_NEAR(v.limit, 306.0, 0.5);
  EXPECT_NE(v.criterion.find("speed"), std::string::npos);
  sim.state_to_change().particles.vx[i] = 300.0;
  EXPECT_TRUE(sim.check_stability().ok) << "300 m/s is below c_d";
}

TEST(Stability, InvertedBondIsFoundByThePaperModels) {
  for (const std::string model : {"paper", "paper_conservative"}) {
    Simulation sim(testing::rod_case({"model=" + model}));
    ParticleStore& p = sim.state_to_change().particles;
    // Push an interior rod particle through its right-hand neighbour.
    std::size_t i = p.size(), j = p.size();
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (std::abs(p.x0[k] - 0.021) < 1e-9 && std::abs(p.y0[k] - 0.001) < 1e-9) i = k;
      if (std::abs(p.x0[k] - 0.023) < 1e-9 && std::abs(p.y0[k] - 0.001) < 1e-9) j = k;
    }
    ASSERT_LT(i, p.size());
    p.x[i] += 2.5e-3;
    const StabilityVerdict v = sim.check_stability();
    EXPECT_FALSE(v.ok) << model;
    EXPECT_NE(v.criterion.find("inside out"), std::string::npos);
    EXPECT_TRUE((v.particle == i && v.neighbor == j) || (v.particle == j && v.neighbor == i))
        << "reported " << p.id[v.particle] << " and " << p.id[v.neighbor];
  }
}

TEST(Stability, CollapsedNeighbourhoodIsFoundByFiniteStrain) {
  Simulation sim(testing::rod_case({"model=finite_strain", "stability.min_jacobian=0.5"}));
  ParticleStore& p = sim.state_to_change().particles;
  // Squeeze the rod to 40 % of its length: J = 0.4 everywhere in it.
  for (std::size_t k = p.elastic.begin; k < p.elastic.end; ++k)
    p.x[k] = 0.1 - 0.4 * (0.1 - p.x0[k]);
  const StabilityVerdict v = sim.check_stability();
  EXPECT_FALSE(v.ok);
  EXPECT_NE(v.criterion.find("J"), std::string::npos);
  EXPECT_LT(v.value, 0.5);
}

TEST(Stability, EnergyCheckWaitsForTheHalfStepLagToFade) {
  // At a large step the first checks see KE lag W by about 1/(2k): not a blow-up.
  Simulation sim(testing::rod_case({"time.dt=2e-6", "stability.check_interval=5"}));
  for (int k = 0; k < 40; ++k) {
    sim.advance(5);
    const StabilityVerdict v = sim.check_stability();
    ASSERT_TRUE(v.ok) << "step " << sim.step() << ": " << v.criterion;
  }
}

TEST(Stability, EnergyBalance) {
  Diagnostics d;
  d.kinetic_energy = 50.0;
  d.strain_energy = 40.0;
  d.external_work = 100.0;
  EXPECT_FALSE(check_energy(d, 0.0, 0.0, 0.05).ok);  // 10 % off
  EXPECT_TRUE(check_energy(d, 0.0, 0.0, 0.2).ok);
  EXPECT_TRUE(check_energy(d, 0.0, 250.0, 0.05).ok);  // 4 % of the peak work
  d.external_work = 0.0;  // free motion: measured against the initial energy
  EXPECT_TRUE(check_energy(d, 90.0, 0.0, 0.01).ok);
  EXPECT_FALSE(check_energy(d, 80.0, 0.0, 0.1).ok);
  // A body at rest before any load: its round-off energy is below the floor.
  Diagnostics rest;
  rest.strain_energy = 3e-20;
  EXPECT_FALSE(check_energy(rest, 1e-25, 0.0, 0.1).ok);
  EXPECT_TRUE(check_energy(rest, 1e-25, 0.0, 0.1, 1e-5).ok);
}

}  // namespace
}  // namespace mpsolid
