// Per-bond maths: antisymmetry of u, and the strain of an affine field.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/bond_math.hpp"
#include "kernels/paper_model.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(BondMath, DisplacementIsAntisymmetricBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100000; ++trial) {
    const double xi = u(rng), yi = u(rng), xj = u(rng), yj = u(rng);
    const double ti = 3 * u(rng), tj = 3 * u(rng);
    const double r0x = u(rng), r0y = u(rng);
    const auto rij = bond_math::bond_rotation(std::cos(ti / 2), std::sin(ti / 2), std::cos(tj / 2),
                                              std::sin(tj / 2));
    const auto rji = bond_math::bond_rotation(std::cos(tj / 2), std::sin(tj / 2), std::cos(ti / 2),
                                              std::sin(ti / 2));
    const auto a = bond_math::bond_vectors(xi, yi, xj, yj, rij, r0x, r0y);
    const auto b = bond_math::bond_vectors(xj, yj, xi, yi, rji, -r0x, -r0y);
    ASSERT_EQ(a.ux, -b.ux);
    ASSERT_EQ(a.uy, -b.uy);
    ASSERT_EQ(a.rx, -b.rx);
    ASSERT_EQ(a.ry, -b.ry);
  }
}

TEST(BondMath, HalfAngleIdentityGivesTheMeanRotation) {
  for (double ti : {-2.0, 0.0, 0.3, 1.0, 3.1})
    for (double tj : {-1.0, 0.0, 0.7, 2.5}) {
      const auto r = bond_math::bond_rotation(std::cos(ti / 2), std::sin(ti / 2), std::cos(tj / 2),
                                              std::sin(tj / 2));
      EXPECT_NEAR(r.cos, std::cos((ti + tj) / 2), 1e-15);
      EXPECT_NEAR(r.sin, std::sin((ti + tj) / 2), 1e-15);
    }
}

TEST(BondMath, WeightFunction) {
  EXPECT_DOUBLE_EQ(bond_math::weight(1.0, 2.1), 1.1);
  EXPECT_EQ(bond_math::weight(2.1, 2.1), 0.0);
  EXPECT_EQ(bond_math::weight(3.0, 2.1), 0.0);
  EXPECT_EQ(bond_math::weight(0.0, 2.1), 0.0);
}

// An affine map r = r0 + G r0 (G small, symmetric part S, antisymmetric part
// W): with theta = the rotation of G, interior particles get eps = tr(S) and
// zero force, to first order in G.
TEST(PaperModel, AffineDisplacementGivesAnalyticStrainInTheInterior) {
  Simulation sim(testing::free_block_case(24, 24, false));
  ParticleStore& p = sim.state_to_change().particles;
  const double g[2][2] = {{2.0e-6, 0.7e-6}, {-0.3e-6, -1.1e-6}};
  const double rotation = 0.5 * (g[1][0] - g[0][1]);
  const double trace = g[0][0] + g[1][1];
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.x[i] = p.x0[i] + g[0][0] * p.x0[i] + g[0][1] * p.y0[i];
    p.y[i] = p.y0[i] + g[1][0] * p.x0[i] + g[1][1] * p.y0[i];
    p.theta[i] = rotation;
  }
  sim.refresh_fields();
  testing::run_model_passes<PaperModel>(p, sim.state().bonds);
  const double l0 = sim.spec().l0;
  const double lambda = p.lambda[0];
  const double mu = p.mu[0];
  // Force scale of one bond at this strain, for a relative tolerance.
  const double force_scale = (lambda + 2 * mu) * 1e-6 * l0 * sim.spec().depth;
  int checked = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double margin = 4.0 * l0;  // strain needs 2 layers, force 2 more
    if (p.x0[i] < margin || p.x0[i] > 24 * l0 - margin || p.y0[i] < margin ||
        p.y0[i] > 24 * l0 - margin)
      continue;
    ++checked;
    EXPECT_NEAR(p.strain[i], trace, 1e-5 * std::abs(trace)) << "particle " << i;
    EXPECT_NEAR(p.pressure[i], -lambda * trace, 1e-5 * lambda * std::abs(trace));
    EXPECT_NEAR(p.fx[i], 0.0, 1e-5 * force_scale);
    EXPECT_NEAR(p.fy[i], 0.0, 1e-5 * force_scale);
  }
  EXPECT_EQ(checked, 16 * 16);
  // A surface particle feels the unbalanced stress: the test can fail.
  EXPECT_GT(std::abs(p.fx[0]) + std::abs(p.fy[0]), 0.1 * force_scale);
}

}  // namespace
}  // namespace mpsolid
