// Lagrange's ideal gun: a free rigid piston pushed along a tube by a gas
// column at rest, vacuum behind it. Until the rarefaction the piston starts
// comes back from the tube's closed end, the gas at the piston is a simple
// wave, p = p0 (1 - (gamma - 1) v / (2 c0))^(2 gamma / (gamma - 1)), and the
// piston's velocity follows m dv/dt = p A exactly (integrated here by RK4).
// The run couples the gas solver to a rigid body of particles through the
// body's surface; docs/gas.md has the figures.
//
// And a piston held between two gas columns (the gas is its spring),
// closed tubes of lengths L1 and L2, set moving slowly: it oscillates at
// the lowest root of the acoustic frequency equation
// m omega^2 = rho0 c0 omega (cot(omega L1 / c0) + cot(omega L2 / c0)) per
// unit area, the columns' inertia included (the lumped spring
// rho0 c0^2 (1/L1 + 1/L2) alone is 4 % off here).
//
// And a piston driven into air at rest, started impulsively at 3 km/s
// (Mach 8.6): a shock of exactly known pressure and speed
// (Rankine-Hugoniot), which outruns the gas's own |u| + c at the start;
// the window and the gas step must follow the jump.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/gas/wall_riemann.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/gas_coupling.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid {
namespace {

constexpr double kP0 = 1e6, kRho0 = 10, kGamma = 1.4;
constexpr double kTube = 0.01, kStart = 0.3;  // m: tube height, piston's face
constexpr double kPistonRho = 100.0 / 3, kPistonLength = 0.3, kPistonHeight = 0.02;

std::string gun_case(double cell) {
  return fmt::format(R"(name = "gun"
model = "finite_strain"
l0 = 0.0025
[materials.light]
E = 1e9
nu = 0.3
rho = {rho}
[bodies.piston]
kind = "rigid"
material = "light"
x = [{x0}, {x1}]
y = [-0.005, 0.015]
[time]
dt = 1e-6
end = 0.0015
[output]
frame_interval = 0.0015
[gas]
cell = {cell}
x = [0.0, 0.5]
y = [0.0, {tube}]
reference_pressure = 0.0
[gas.initial]
density = {rho0}
pressure = {p0}
)",
                     fmt::arg("rho", kPistonRho), fmt::arg("x0", kStart),
                     fmt::arg("x1", kStart + kPistonLength), fmt::arg("cell", cell),
                     fmt::arg("tube", kTube), fmt::arg("rho0", kRho0), fmt::arg("p0", kP0));
}

// The piston's exact velocity at t (RK4, 4000 steps).
double exact_velocity(double t) {
  const double c0 = std::sqrt(kGamma * kP0 / kRho0);
  const double mass_per_area = kPistonRho * kPistonLength * kPistonHeight / kTube;
  const auto a = [&](double v) {
    return kP0 * std::pow(1 - 0.5 * (kGamma - 1) * v / c0, 2 * kGamma / (kGamma - 1)) /
           mass_per_area;
  };
  double v = 0;
  const int n = 4000;
  const double h = t / n;
  for (int k = 0; k < n; ++k) {
    const double k1 = a(v), k2 = a(v + 0.5 * h * k1), k3 = a(v + 0.5 * h * k2), k4 = a(v + h * k3);
    v += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  return v;
}

TEST(IdealGun, APistonPushedByAGasColumnFollowsLagrangesExactVelocity) {
  for (const double cell : {0.0025, 0.00125}) {
    Simulation sim(load_case_text(gun_case(cell), "gun.toml"));
    const Diagnostics d0 = sim.diagnostics();
    const GasFigures g0 = d0.gas;
    double worst = 0;
    for (int k = 1; k <= 5; ++k) {
      sim.advance(300);  // to 0.3, 0.6, ... 1.5 ms: before the rarefaction comes back
      const double v = sim.state().rigid_bodies.at(0).vx;
      const double exact = exact_velocity(sim.time());
      worst = std::max(worst, std::abs(v / exact - 1));
    }
    const Diagnostics d = sim.diagnostics();
    const GasFigures g = d.gas;
    // The gas gives the piston its energy: what one loses the other gains.
    const double total0 = g0.energy + d0.kinetic_energy, total = g.energy + d.kinetic_energy;
    const double imbalance = (total - total0) / d.kinetic_energy;
    const double gas_balance = (g.energy - g0.energy + g.wall_work) / g0.energy;
    std::printf(
        "cell %.5f m: piston velocity within %.4f %% of exact to 1.5 ms (%.4f m/s at the end), "
        "gas + piston energy off by %.3f %% of the piston's (coupling error %.3f %%), gas balance "
        "%.1e, %lld gas steps\n",
        cell, 100 * worst, sim.state().rigid_bodies.at(0).vx, 100 * imbalance,
        100 * g.coupling_error / d.kinetic_energy, gas_balance,
        static_cast<long long>(g.gas_steps));
    EXPECT_LT(worst, 0.001);
    EXPECT_LT(std::abs(imbalance), 0.005);
    EXPECT_LT(std::abs(gas_balance), 1e-12);
  }
}

// The lowest root of the frequency equation (bisection below the columns'
// first modes).
double column_frequency(double mass_per_area, double l1, double l2) {
  const double c0 = std::sqrt(kGamma * 101325.0 / 1.2), rho0 = 1.2;
  const auto f = [&](double w) {
    return mass_per_area * w * w -
           rho0 * c0 * w * (1 / std::tan(w * l1 / c0) + 1 / std::tan(w * l2 / c0));
  };
  double lo = 1e-6, hi = 0.999 * M_PI * c0 / std::max(l1, l2);
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(GasSpring, APistonBetweenTwoGasColumnsOscillatesAtTheirFrequencyEquationsRoot) {
  const double l1 = 0.3, l2 = 0.2, thick = 0.02, height = 0.02, tube = 0.01, rho_s = 62.5;
  const std::string text =
      fmt::format(R"(name = "gas_spring"
model = "finite_strain"
l0 = 0.0025
[materials.heavy]
E = 1e9
nu = 0.3
rho = {rho}
[bodies.piston]
kind = "rigid"
material = "heavy"
x = [{x0}, {x1}]
y = [-0.005, 0.015]
velocity = [1.0, 0.0]
[time]
dt = 2e-6
end = 0.03
[output]
frame_interval = 0.03
history_interval = 1e-4
[gas]
cell = 0.0025
x = [0.0, {end}]
y = [0.0, {tube}]
[gas.initial]
density = 1.2
pressure = 101325.0
)",
                  fmt::arg("rho", rho_s), fmt::arg("x0", l1), fmt::arg("x1", l1 + thick),
                  fmt::arg("end", l1 + thick + l2), fmt::arg("tube", tube));
  // One thread: a few hundred cells and 64 particles, a window every few steps.
  const int threads = thread_count();
  set_thread_count(1);
  Simulation sim(load_case_text(text, "gas_spring.toml"));
  // The piston's displacement's downward zero crossings, by linear
  // interpolation between rows.
  std::vector<double> crossings;
  double last_x = 0, last_t = 0;
  while (sim.step() < sim.spec().step_count()) {
    sim.advance(50);
    const double x = sim.state().rigid_bodies.at(0).xg - sim.state().rigid_bodies.at(0).xg0;
    const double t = sim.time();
    if (last_x > 0 && x <= 0) crossings.push_back(last_t + (t - last_t) * last_x / (last_x - x));
    last_x = x;
    last_t = t;
  }
  set_thread_count(threads);
  ASSERT_GE(crossings.size(), 2u);
  const double period =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  const double mass_per_area = rho_s * thick * height / tube;
  const double exact = 2 * M_PI / column_frequency(mass_per_area, l1, l2);
  const double lumped = 2 * M_PI / std::sqrt(kGamma * 101325.0 * (1 / l1 + 1 / l2) / mass_per_area);
  std::printf(
      "gas spring: period %.5f ms over %zu periods (frequency equation %.5f ms, lumped "
      "spring %.5f ms): %+.3f %%\n",
      1e3 * period, crossings.size() - 1, 1e3 * exact, 1e3 * lumped, 100 * (period / exact - 1));
  EXPECT_NEAR(period / exact, 1.0, 0.005);
  EXPECT_GT(std::abs(lumped / exact - 1), 0.02);  // the columns' inertia matters here
}

TEST(ImpulsivePiston, APistonStartedAt3KmPerSecondDrivesTheExactShock) {
  const double speed = 3000, start = 1e-6, end = 2e-5, face = 0.104;
  const std::string text = fmt::format(R"(name = "impulsive_piston"
model = "finite_strain"
l0 = 0.001
[materials.light]
E = 1e15
nu = 0.3
rho = 1000.0
[bodies.piston]
kind = "rigid"
material = "light"
x = [0.1, {face}]
y = [0.0, 0.004]
[bodies.piston.motion]
velocity = [{speed}, 0.0]
history = "step"
start = {start}
[time]
dt = 1e-8
end = {end}
[output]
frame_interval = {end}
[gas]
cell = 0.001
x = [0.0, 0.2]
y = [0.0, 0.004]
left = "outflow"
right = "outflow"
[gas.initial]
density = 1.2
pressure = 100000.0
)",
                                       fmt::arg("face", face), fmt::arg("speed", speed),
                                       fmt::arg("start", start), fmt::arg("end", end));
  const int threads = thread_count();
  set_thread_count(1);
  Simulation sim(load_case_text(text, "impulsive_piston.toml"));
  sim.advance(sim.spec().step_count());
  set_thread_count(threads);
  ASSERT_FALSE(sim.gas_failed());
  // Exact: the gas behind the shock moves with the piston at p*; the shock
  // runs ahead of it at rho* u / (rho* - rho0).
  const double p_star = wall_pressure(1.2, 0.0, 1e5, kGamma, -speed);
  const double shock = wall_wave_speed(1.2, 0.0, 1e5, kGamma, -speed);
  const GasFrame f = sim.gas_frame();
  const double piston = face + speed * (end - start);
  std::vector<double> behind;  // the shocked gas's cells
  double front = 0;
  for (int i = 0; i < f.nx; ++i) {
    const double x = f.x0 + (i + 0.5) * f.h, p = f.pressure[static_cast<std::size_t>(i)];
    if (x > piston + 0.002 && p > 0.9 * p_star && p < 1.1 * p_star) behind.push_back(p);
    if (x > piston && p > 0.5 * (p_star + 1e5)) front = x;  // the shock's last cell past half
  }
  ASSERT_GT(behind.size(), 5u);
  std::sort(behind.begin(), behind.end());  // the median: the plateau, not its edges
  const double plateau = behind[behind.size() / 2];
  const double exact_front = face + shock * (end - start);
  std::printf("impulsive piston: p* %.1f kPa (exact %.1f), shock at %.2f mm (exact %.2f)\n",
              plateau / 1e3, p_star / 1e3, 1e3 * front, 1e3 * exact_front);
  EXPECT_NEAR(plateau / p_star, 1.0, 0.005);
  EXPECT_NEAR(front, exact_front, 2e-3);
}

}  // namespace
}  // namespace mpsolid
