// The half angles' sin and cos (src/core/half_angles.hpp): within 1 ulp of
// glibc over any angle a run reaches, exact at 0, the right quadrant
// everywhere, and the same bits from the vectorised integration loop as from
// the scalar formula the other writers use.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "src/core/half_angles.hpp"
#include "src/core/integrator.hpp"

namespace mpsolid {
namespace {

// |a - b| in units of b's last place.
double ulps(double a, double b) {
  if (a == b) return 0.0;
  const double ulp = std::nextafter(std::abs(b), INFINITY) - std::abs(b);
  return std::abs(a - b) / ulp;
}

TEST(HalfAngles, WithinOneUlpOfLibmUpToOneHundredThousandRadians) {
  std::mt19937_64 rng(11);
  for (const double range : {0.785, 3.2, 100.0, 1e5}) {
    std::uniform_real_distribution<double> u(-range, range);
    double worst = 0.0;
    for (int k = 0; k < 200000; ++k) {
      const double x = u(rng);
      const SinCos sc = sin_cos(x);
      worst = std::max({worst, ulps(sc.sin, std::sin(x)), ulps(sc.cos, std::cos(x))});
    }
    EXPECT_LE(worst, 1.0) << "|x| < " << range;
  }
}

TEST(HalfAngles, ExactAtZeroAndRightInEveryQuadrant) {
  EXPECT_EQ(sin_cos(0.0).sin, 0.0);
  EXPECT_EQ(sin_cos(0.0).cos, 1.0);
  const HalfAngle h = half_angle(0.0);  // walls: exactly no rotation
  EXPECT_EQ(h.cos, 1.0);
  EXPECT_EQ(h.sin, 0.0);
  for (double x = -20.0; x <= 20.0; x += 0.37) {
    const SinCos sc = sin_cos(x);
    EXPECT_NEAR(sc.sin, std::sin(x), 1e-15) << x;
    EXPECT_NEAR(sc.cos, std::cos(x), 1e-15) << x;
  }
}

TEST(HalfAngles, IntegrationLoopGivesTheBitsOfTheScalarFormula) {
  ParticleStore p;
  p.resize(1000);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 2.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.theta[i] = n(rng);
    p.omega[i] = n(rng);
    p.torque[i] = n(rng);
    p.inv_inertia[i] = 1.0;
    p.inv_mass[i] = 1.0;
  }
  kick_drift(p, {0, p.size()}, 1e-3, true);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const HalfAngle h = half_angle(p.theta[i]);
    ASSERT_EQ(p.half_cos[i], h.cos) << i;
    ASSERT_EQ(p.half_sin[i], h.sin) << i;
  }
}

}  // namespace
}  // namespace mpsolid
