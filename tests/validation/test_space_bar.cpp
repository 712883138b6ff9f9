// A steel bar in space (kernels/gradient_gather_model.hpp stepped by
// src/solver/step.hpp). Free, its first longitudinal mode rings at the bar
// wave speed sqrt(E / rho), f = c / (2 L) with Love's lateral-inertia
// correction; with every particle's lateral motion held (uniaxial strain),
// at the dilatational wave speed sqrt((lambda + 2 mu) / rho). The errors
// fall as the spacing is halved.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kernels/finite_strain_model.hpp"
#include "kernels/gradient_gather_model.hpp"
#include "neighbor/bond_search.hpp"
#include "src/solver/step.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

constexpr double kLength = 0.030, kSide = 0.003;  // m
constexpr double kLambda = 1.15e11, kMu = 7.7e10, kDensity = 7850.0;

double youngs_modulus() {
  return kMu * (3 * kLambda + 2 * kMu) / (kLambda + kMu);
}
double poisson_ratio() {
  return kLambda / (2 * (kLambda + kMu));
}

// Free: Love's rod theory, omega = c k (1 - nu^2 k^2 r^2 / 2), r^2 =
// side^2 / 6 the square section's polar radius of gyration squared.
// Confined: c = sqrt((lambda + 2 mu) / rho), no dispersion.
double expected_frequency(bool confined) {
  if (confined) return std::sqrt((kLambda + 2 * kMu) / kDensity) / (2 * kLength);
  const double c = std::sqrt(youngs_modulus() / kDensity), k = std::numbers::pi / kLength;
  const double nu = poisson_ratio(), r2 = kSide * kSide / 6;
  return c / (2 * kLength) * (1 - 0.5 * nu * nu * k * k * r2);
}

// The bar at spacing l0, started in its first mode, u_x = A cos(pi x / L);
// the frequency from the zero crossings of its left end's mean u_x over two
// periods. Confined: each step puts every particle back on its y0 and z0
// at rest laterally.
double ringing_frequency(double l0, bool confined) {
  const int nx = static_cast<int>(std::lround(kLength / l0));
  const int ny = static_cast<int>(std::lround(kSide / l0));
  SolverState s;
  s.particles = testing::space_block(nx, ny, ny, l0, kLambda, kMu, kDensity);
  s.bonds = build_bonds(s.particles, bond_geometry_3d(l0));
  ParticleStore& p = s.particles;
  const double amplitude = 1e-5 * kLength;
  for (std::size_t i = 0; i < p.size(); ++i)
    p.x[i] += amplitude * std::cos(std::numbers::pi * p.x0[i] / kLength);
  GradientGatherModel<3, NeoHookeanLaw> model(p, s.bonds,
                                              default_options(hourglass_option_table()));
  const double c_dilatational = std::sqrt((kLambda + 2 * kMu) / kDensity);
  const double dt = 0.2 * l0 / c_dilatational;
  const double period = 1.0 / expected_frequency(confined);
  const std::int64_t steps = std::llround(2.2 * period / dt);
  const auto end_displacement = [&] {
    double sum = 0;
    int count = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.x0[i] < l0) sum += p.x[i] - p.x0[i], ++count;
    return sum / count;
  };
  PhaseTimers timers;
  std::vector<double> crossings;
  double before = end_displacement();
  for (std::int64_t k = 1; k <= steps; ++k) {
    advance_steps(model, s, dt, timers, 1);
    if (confined) {
      p.y = p.y0;
      p.z = p.z0;
      std::fill(p.vy.begin(), p.vy.end(), 0.0);
      std::fill(p.vz.begin(), p.vz.end(), 0.0);
    }
    const double now = end_displacement();
    if ((before > 0) != (now > 0))
      crossings.push_back((static_cast<double>(k - 1) + before / (before - now)) * dt);
    before = now;
  }
  EXPECT_GE(crossings.size(), 4u);
  // Crossings are half a period apart.
  return 0.5 * static_cast<double>(crossings.size() - 1) / (crossings.back() - crossings.front());
}

void expect_convergence(bool confined, const char* what) {
  const double expected = expected_frequency(confined);
  const double coarse = std::abs(ringing_frequency(1e-3, confined) / expected - 1);
  const double fine = std::abs(ringing_frequency(0.5e-3, confined) / expected - 1);
  std::printf("%s: relative error %.3e at l0 = 1 mm, %.3e at 0.5 mm\n", what, coarse, fine);
  EXPECT_LT(coarse, 5e-3) << what;
  EXPECT_LT(fine, 0.3 * coarse) << what;
}

TEST(SpaceBar, FirstLongitudinalModeRingsAtTheBarWaveSpeedConvergingWithL0) {
  expect_convergence(false, "bar wave");
}

TEST(SpaceBar, ConfinedModeRingsAtTheDilatationalWaveSpeedConvergingWithL0) {
  expect_convergence(true, "dilatational wave");
}

}  // namespace
}  // namespace mpsolid
