// The gas solver against exact solutions: the HLLC flux's consistency, the
// exact Riemann solver against Toro's tabulated star states, Sod's shock
// tube (L1 error at three grids), a smooth density pulse (second order), a
// normal shock reflected by a wall against Rankine-Hugoniot, mass and energy
// in a closed box, and the same bits along any axis in 2D and 3D.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/gas/exact_riemann.hpp"
#include "src/gas/gas_solver.hpp"
#include "src/gas/hllc_flux.hpp"
#include "src/gas/shock_relations.hpp"

namespace mpsolid {
namespace {

constexpr double kGamma = 1.4;

TEST(GasFlux, HllcOfTwoEqualStatesIsTheEulerFlux) {
  const GasPrimitive<2> w{1.3, {120.0, -45.0}, 2.1e5};
  for (int axis = 0; axis < 2; ++axis) {
    const GasConserved<2> f = hllc_flux(w, w, kGamma, axis), e = euler_flux(w, kGamma, axis);
    EXPECT_NEAR(f.rho, e.rho, 1e-12 * std::abs(e.rho));
    for (int d = 0; d < 2; ++d) EXPECT_NEAR(f.m[d], e.m[d], 1e-12 * (std::abs(e.m[d]) + w.p));
    EXPECT_NEAR(f.E, e.E, 1e-12 * std::abs(e.E));
  }
}

TEST(GasFlux, HllcResolvesAStationaryContactExactly) {
  // Two densities at one pressure and no velocity: nothing moves.
  const GasPrimitive<2> l{1.0, {0.0, 3.0}, 1e5}, r{0.125, {0.0, -2.0}, 1e5};
  const GasConserved<2> f = hllc_flux(l, r, kGamma, 0);
  EXPECT_EQ(f.rho, 0.0);
  EXPECT_DOUBLE_EQ(f.m[0], 1e5);
  EXPECT_EQ(f.m[1], 0.0);
  EXPECT_EQ(f.E, 0.0);
}

TEST(ExactRiemann, StarStatesMatchToroTable) {
  // Toro, table 4.2: tests 1 (Sod), 2 (123 problem) and 3.
  struct Case {
    GasState1D l, r;
    double p, u;
  };
  for (const Case& c : {Case{{1.0, 0.0, 1.0}, {0.125, 0.0, 0.1}, 0.30313, 0.92745},
                        Case{{1.0, -2.0, 0.4}, {1.0, 2.0, 0.4}, 0.00189, 0.0},
                        Case{{1.0, 0.0, 1000.0}, {1.0, 0.0, 0.01}, 460.894, 19.5975}}) {
    const ExactRiemann r(c.l, c.r, kGamma);
    EXPECT_NEAR(r.star_pressure(), c.p, 1e-5 * std::max(1.0, c.p));
    EXPECT_NEAR(r.star_velocity(), c.u, 1e-5 * std::max(1.0, std::abs(c.u)));
  }
}

// A tube along axis 0 of a 2D grid one cell high, [0, 1] in n cells.
GasSolver<2> tube(int n, GasBoundaryKind low, GasBoundaryKind high,
                  const std::function<GasState1D(double)>& initial) {
  GasGrid<2> g;
  g.cells = {n, 1};
  g.h = 1.0 / n;
  GasSolver<2>::Boundaries b;
  b[0][0].kind = low;
  b[0][1].kind = high;
  GasSolver<2> gas(g, kGamma, b);
  for (int i = 0; i < n; ++i) {
    const GasState1D s = initial(g.centre({i, 0})[0]);
    gas.set({i, 0}, GasPrimitive<2>{s.rho, {s.u, 0.0}, s.p});
  }
  return gas;
}

// Runs from `start` to `end` at CFL 0.8, the last step shortened to land
// on it.
template <int Dim>
void run_to(GasSolver<Dim>& gas, double end, double start = 0) {
  double t = start;
  while (t < end) {
    const double dt = std::min(gas.stable_dt(0.8), end - t);
    gas.advance(dt);
    t += dt;
  }
}

double sod_l1_error(int n) {
  const GasState1D left{1.0, 0.0, 1.0}, right{0.125, 0.0, 0.1};
  GasSolver<2> gas = tube(n, GasBoundaryKind::outflow, GasBoundaryKind::outflow,
                          [&](double x) { return x < 0.5 ? left : right; });
  run_to(gas, 0.2);
  const ExactRiemann exact(left, right, kGamma);
  double error = 0;
  for (int i = 0; i < n; ++i) {
    const double x = gas.grid().centre({i, 0})[0];
    error += std::abs(gas.primitive({i, 0}).rho - exact.sample((x - 0.5) / 0.2).rho) / n;
  }
  return error;
}

TEST(GasSolver, SodShockTubeConvergesToTheExactSolution) {
  const double e100 = sod_l1_error(100), e200 = sod_l1_error(200), e400 = sod_l1_error(400);
  std::printf("Sod L1(rho): %.4e %.4e %.4e, orders %.2f %.2f\n", e100, e200, e400,
              std::log2(e100 / e200), std::log2(e200 / e400));
  EXPECT_LT(e100, 0.01);
  // Shocks and contacts make it first order at best in L1.
  EXPECT_GT(std::log2(e100 / e400) / 2, 0.7);
}

double pulse_l1_error(int n) {
  const auto rho = [](double x) { return 1.0 + 0.2 * std::exp(-std::pow((x - 0.3) / 0.1, 2)); };
  GasSolver<2> gas = tube(n, GasBoundaryKind::outflow, GasBoundaryKind::outflow, [&](double x) {
    return GasState1D{rho(x), 1.0, 1.0};
  });
  run_to(gas, 0.4);
  double error = 0;
  for (int i = 0; i < n; ++i) {
    const double x = gas.grid().centre({i, 0})[0];
    error += std::abs(gas.primitive({i, 0}).rho - rho(x - 0.4)) / n;
  }
  return error;
}

TEST(GasSolver, ASmoothPulseConvergesAtSecondOrder) {
  const double e100 = pulse_l1_error(100), e200 = pulse_l1_error(200), e400 = pulse_l1_error(400);
  std::printf("pulse L1(rho): %.4e %.4e %.4e, orders %.2f %.2f\n", e100, e200, e400,
              std::log2(e100 / e200), std::log2(e200 / e400));
  // Second order but for the limiter, which flattens the pulse's peak.
  EXPECT_GT(std::log2(e100 / e200), 1.7);
  EXPECT_GT(std::log2(e200 / e400), 1.7);
}

TEST(GasSolver, AShockReflectedByAWallMatchesRankineHugoniot) {
  const GasState1D air{1.2, 0.0, 101000.0};
  for (const double mach : {1.21, 1.5, 2.0}) {
    const ShockedGas incident = shocked_gas(air, mach, kGamma);
    const ReflectedShock reflected = reflected_shock(incident.behind, kGamma);
    // The shock starts at x = 0.5 and runs into the wall at x = 1.
    const int n = 800;
    GasSolver<2> gas = tube(n, GasBoundaryKind::outflow, GasBoundaryKind::slip_wall,
                            [&](double x) { return x < 0.5 ? incident.behind : air; });
    const double at_wall = 0.5 / incident.shock_speed;
    // Where the pressure crosses halfway between the incident and the
    // reflected shocks' pressures, scanning from the wall.
    const auto front = [&] {
      const double level = 0.5 * (incident.behind.p + reflected.at_wall.p);
      for (int i = n - 1; i > 0; --i) {
        const double p1 = gas.primitive({i, 0}).p, p0 = gas.primitive({i - 1, 0}).p;
        if (p1 >= level && p0 < level) {
          const double x1 = gas.grid().centre({i, 0})[0];
          return x1 - gas.grid().h * (p1 - level) / (p1 - p0);
        }
      }
      return 0.0;
    };
    const double t1 = at_wall + 0.1 / reflected.shock_speed,
                 t2 = at_wall + 0.3 / reflected.shock_speed;
    run_to(gas, t1);
    const double x1 = front();
    run_to(gas, t2, t1);
    const double x2 = front();
    const double speed = (x1 - x2) / (t2 - t1);
    const double wall_p = gas.primitive({n - 1, 0}).p;
    std::printf("Mach %.2f: reflected p %.6g Pa (exact %.6g), speed %.5g m/s (exact %.5g)\n", mach,
                wall_p, reflected.at_wall.p, speed, reflected.shock_speed);
    EXPECT_NEAR(wall_p / reflected.at_wall.p, 1.0, 0.005);
    EXPECT_NEAR(speed / reflected.shock_speed, 1.0, 0.005);
  }
}

// A closed 2D box with a hot, dense blob off its centre.
GasSolver<2> box_with_blob() {
  GasGrid<2> g;
  g.cells = {40, 30};
  g.h = 0.01;
  GasSolver<2> gas(g, kGamma, {});
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) {
      const double r = std::hypot(i - 12.3, j - 17.1);
      gas.set({i, j}, GasPrimitive<2>{r < 6 ? 3.0 : 1.2, {0.0, 0.0}, r < 6 ? 5e5 : 1e5});
    }
  return gas;
}

TEST(GasSolver, AClosedBoxKeepsItsMassAndEnergy) {
  GasSolver<2> gas = box_with_blob();
  const GasTotals<2> before = gas.totals();
  run_to(gas, 2e-3);
  const GasTotals<2> after = gas.totals();
  EXPECT_NEAR(after.mass, before.mass, 1e-13 * before.mass);
  EXPECT_NEAR(after.energy, before.energy, 1e-13 * before.energy);
}

TEST(GasSolver, AStepThatWouldGoUnphysicalThrowsAndLeavesTheGasAsItWas) {
  // Ten times the stable step on Sod's tube empties a cell past zero.
  GasSolver<2> gas = tube(100, GasBoundaryKind::outflow, GasBoundaryKind::outflow, [](double x) {
    return x < 0.5 ? GasState1D{1.0, 0.0, 1.0} : GasState1D{0.125, 0.0, 0.1};
  });
  run_to(gas, 0.05);
  std::vector<std::vector<double>> before;
  for (int v = 0; v < GasSolver<2>::kVars; ++v) before.push_back(gas.conserved(v));
  const GasExchange<2> exchange = gas.exchange();
  try {
    gas.advance(10 * gas.stable_dt(0.8));
    FAIL() << "a step ten times the stable one went through";
  } catch (const GasFailure& e) {
    EXPECT_NE(std::string(e.what()).find("went unphysical in cell ("), std::string::npos)
        << e.what();
  }
  for (int v = 0; v < GasSolver<2>::kVars; ++v)
    for (int i = 0; i < 100; ++i) {
      const std::size_t k = gas.grid().index({i, 0});
      EXPECT_EQ(gas.conserved(v)[k], before[v][k]) << v << " " << i;
    }
  EXPECT_EQ(gas.exchange().inflow.energy, exchange.inflow.energy);
  EXPECT_EQ(gas.exchange().inflow.mass, exchange.inflow.mass);
  // And it goes on from there as if nothing happened.
  run_to(gas, 0.2, 0.05);
  EXPECT_GT(gas.primitive({50, 0}).p, 0.0);
}

TEST(GasSolver, SameBitsAt1To4Threads) {
  const int threads = thread_count();
  std::vector<std::vector<double>> first;
  for (int t = 1; t <= 4; ++t) {
    set_thread_count(t);
    GasSolver<2> gas = box_with_blob();
    run_to(gas, 1e-3);
    std::vector<std::vector<double>> fields;
    for (int v = 0; v < GasSolver<2>::kVars; ++v) fields.push_back(gas.conserved(v));
    if (t == 1)
      first = fields;
    else
      EXPECT_EQ(fields, first) << t << " threads";
  }
  set_thread_count(threads);
}

TEST(GasSolver, AnyAxisGivesTheSameBitsIn2DAnd3D) {
  const int n = 64;
  const auto state = [&](int i) {
    return i < n / 2 ? GasPrimitive<3>{1.0, {}, 1.0} : GasPrimitive<3>{0.125, {}, 0.1};
  };
  const auto run_along = [&](auto grid_dim, int axis) {
    constexpr int Dim = decltype(grid_dim)::value;
    GasGrid<Dim> g;
    g.cells.fill(1);
    g.cells[axis] = n;
    g.h = 1.0 / n;
    typename GasSolver<Dim>::Boundaries b;
    b[axis][0].kind = b[axis][1].kind = GasBoundaryKind::outflow;
    GasSolver<Dim> gas(g, kGamma, b);
    for (int i = 0; i < n; ++i) {
      std::array<int, Dim> c{};
      c[axis] = i;
      GasPrimitive<Dim> w;
      w.rho = state(i).rho;
      w.p = state(i).p;
      gas.set(c, w);
    }
    for (int k = 0; k < 40; ++k) gas.advance(0.4 / n);
    std::vector<double> rho;
    for (int i = 0; i < n; ++i) {
      std::array<int, Dim> c{};
      c[axis] = i;
      rho.push_back(gas.primitive(c).rho);
    }
    return rho;
  };
  const std::vector<double> x2 = run_along(std::integral_constant<int, 2>{}, 0);
  EXPECT_EQ(x2, run_along(std::integral_constant<int, 2>{}, 1));
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_EQ(x2, run_along(std::integral_constant<int, 3>{}, axis)) << "axis " << axis;
}

}  // namespace
}  // namespace mpsolid
