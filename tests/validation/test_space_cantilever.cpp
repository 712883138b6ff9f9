// A cantilever in space (cases/cantilever_beam.toml: rubber, 100 x 5 x 5 mm,
// clamped by a wall, started in its first bending mode): the tip's first
// peak comes a quarter period after the start, and the frequency it gives
// converges with l0 towards Euler-Bernoulli's (shear and rotary inertia
// lower the exact value by about 0.15 % at L / h = 20, by Timoshenko's
// first-order correction).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

struct Swing {
  double omega;      // rad/s, from the first peak's time
  double amplitude;  // m, the tip's first peak
};

// The tip's first peak of y: sampled every few steps, the peak's time from a
// parabola through the largest sample and its neighbours.
Swing first_swing(int particles_across) {
  const double l0 = 0.005 / particles_across;
  const CaseSpec spec =
      load_case(testing::source_path("cases/cantilever_beam.toml"), {"l0=" + std::to_string(l0)});
  Simulation sim(spec);
  const std::size_t tip = sim.state().probes.at(0);
  const double y0 = sim.particles().y[tip];
  std::vector<double> t, y;
  const auto every = std::max<std::int64_t>(1, std::llround(2e-4 / sim.spec().dt));
  const auto past_the_peak = [&] {
    return sim.time() > 0.05 && y.size() >= 3 && y.back() < y[y.size() - 2];
  };
  while (!past_the_peak() && sim.time() < 0.2) {
    sim.advance(every);
    t.push_back(sim.time());
    y.push_back(sim.particles().y[tip] - y0);
  }
  EXPECT_TRUE(past_the_peak()) << "no peak by t = 0.2 s";
  const std::size_t k = y.size() - 2;  // the largest sample
  // y = a t^2 + b t + c through three equally spaced samples: the vertex.
  const double h = t[k + 1] - t[k];
  const double a = (y[k + 1] - 2 * y[k] + y[k - 1]) / (2 * h * h);
  const double b = (y[k + 1] - y[k - 1]) / (2 * h);
  const double peak = t[k] - b / (2 * a);
  return {M_PI / 2 / peak, y[k] - b * b / (4 * a)};
}

TEST(SpaceCantilever, FirstBendingFrequencyConvergesToBeamTheory) {
  const double e = 2.0e6, rho = 1000.0, h = 0.005, length = 0.1, kl = 1.875;
  const double omega_beam = kl * kl / (length * length) * h / std::sqrt(12.0) * std::sqrt(e / rho);
  const Swing coarse = first_swing(4), fine = first_swing(6);
  const double error_coarse = 1 - coarse.omega / omega_beam;
  const double error_fine = 1 - fine.omega / omega_beam;
  std::printf("omega %.4f (4 across), %.4f (6 across), beam theory %.4f rad/s\n", coarse.omega,
              fine.omega, omega_beam);
  // Measured 2026-12-05: 13.8 % and 7.0 % low (9.8 % at 5 across, 4.4 % at
  // 8), an order of about 1.65 in l0.
  EXPECT_GT(error_coarse, 0.10);
  EXPECT_LT(error_coarse, 0.17);
  EXPECT_GT(error_fine, 0.05);
  EXPECT_LT(error_fine, 0.09);
  const double order = std::log(error_coarse / error_fine) / std::log(6.0 / 4.0);
  EXPECT_GT(order, 1.3);
  EXPECT_LT(order, 2.0);
  // The amplitude is the tip velocity over the frequency, as in the start.
  EXPECT_NEAR(fine.amplitude * fine.omega / 0.01, 1.0, 0.02);
}

}  // namespace
}  // namespace mpsolid
