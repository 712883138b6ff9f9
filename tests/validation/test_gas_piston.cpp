// Lagrange's ideal gun: a free rigid piston pushed along a tube by a gas
// column at rest, vacuum behind it. Until the rarefaction the piston starts
// comes back from the tube's closed end, the gas at the piston is a simple
// wave, p = p0 (1 - (gamma - 1) v / (2 c0))^(2 gamma / (gamma - 1)), and the
// piston's velocity follows m dv/dt = p A exactly (integrated here by RK4).
// The run couples the gas solver to a rigid body of particles through the
// body's surface; docs/gas.md has the figures.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

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

}  // namespace
}  // namespace mpsolid
