// Walls inside the gas grid: the half Riemann problem at a moving wall
// against the exact Riemann solver, gas at rest round walls staying at rest
// to the bit with no net force, no gas through a plate thinner than a cell,
// solid cells by the outlines' parity, a piston pushed into and drawn out of
// a tube against the exact solution, and the gas's balance of mass,
// momentum and energy with what it exchanged.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/gas/exact_riemann.hpp"
#include "src/gas/gas_solver.hpp"
#include "src/gas/wall_riemann.hpp"

namespace mpsolid {
namespace {

constexpr double kGamma = 1.4;
using Segments = std::vector<GasWallSegment>;

// A closed polygon's segments (counter-clockwise: the body on the left),
// all moving at `v`.
Segments outline(const std::vector<std::array<double, 2>>& corners, std::array<double, 2> v = {}) {
  Segments s;
  for (std::size_t i = 0; i < corners.size(); ++i)
    s.push_back({corners[i], corners[(i + 1) % corners.size()], v, v});
  return s;
}

Segments rectangle(double x0, double x1, double y0, double y1, std::array<double, 2> v = {}) {
  return outline({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, v);
}

Segments join(Segments a, const Segments& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

GasSolver<2> uniform_box(int nx, int ny, double h, GasPrimitive<2> w) {
  GasGrid<2> g;
  g.cells = {nx, ny};
  g.h = h;
  GasSolver<2> gas(g, kGamma, {});
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) gas.set({i, j}, w);
  return gas;
}

TEST(WallPressure, MatchesTheExactRiemannProblemWithTheGasMirrorImage) {
  // The wall at velocity w sees the gas and its mirror image (velocity
  // 2w - u): the star state between them is at rest relative to the wall.
  const double rho = 1.2, p = 101000;
  for (const double u : {-250.0, -40.0, 0.0, 30.0, 180.0, 600.0})
    for (const double w : {-120.0, 0.0, 75.0}) {
      const ExactRiemann exact({rho, u, p}, {rho, 2 * w - u, p}, kGamma);
      EXPECT_NEAR(wall_pressure(rho, u, p, kGamma, w), exact.star_pressure(),
                  1e-9 * exact.star_pressure())
          << "u " << u << " w " << w;
      EXPECT_NEAR(exact.star_velocity(), w, 1e-7 * (std::abs(w) + 1));
    }
}

TEST(GasWalls, SolidCellsAreTheCellsInsideAnOddNumberOfOutlines) {
  GasSolver<2> gas = uniform_box(40, 30, 0.01, {1.2, {0, 0}, 1e5});
  // A slanted square, a disk-like octagon with a square hole, and a block
  // through the grid's left edge.
  const double c = std::cos(0.4), s = std::sin(0.4);
  std::vector<std::array<double, 2>> square;
  for (const auto& [x, y] : std::vector<std::array<double, 2>>{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
    square.push_back({0.08 + 0.05 * (c * x - s * y), 0.08 + 0.05 * (s * x + c * y)});
  std::vector<std::array<double, 2>> octagon, hole;
  for (int k = 0; k < 8; ++k) {
    const double a = 2 * M_PI * (k + 0.5) / 8;
    octagon.push_back({0.26 + 0.09 * std::cos(a), 0.15 + 0.09 * std::sin(a)});
  }
  hole = {{0.24, 0.13}, {0.24, 0.17}, {0.28, 0.17}, {0.28, 0.13}};  // clockwise
  const Segments walls = join(join(outline(square), join(outline(octagon), outline(hole))),
                              rectangle(-0.5, 0.05, 0.22, 0.27));
  gas.set_walls(walls);
  const auto inside = [&](double x, double y) {
    // Parity of a ray to the right, done the slow way.
    int crossings = 0;
    for (const GasWallSegment& w : walls) {
      const double ya = w.a[1], yb = w.b[1];
      if ((ya > y) == (yb > y)) continue;
      const double xc = w.a[0] + (y - ya) / (yb - ya) * (w.b[0] - w.a[0]);
      if (xc > x) ++crossings;
    }
    return crossings % 2 == 1;
  };
  int solid = 0;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i) {
      const auto x = gas.grid().centre({i, j});
      EXPECT_EQ(gas.solid({i, j}), inside(x[0], x[1])) << i << ", " << j;
      solid += gas.solid({i, j});
      // Every face between a solid and a gas cell is closed.
      if (i > 0 && gas.solid({i, j}) != gas.solid({i - 1, j})) {
        EXPECT_TRUE(gas.closed({i, j}, 0));
      }
      if (j > 0 && gas.solid({i, j}) != gas.solid({i, j - 1})) {
        EXPECT_TRUE(gas.closed({i, j}, 1));
      }
    }
  EXPECT_GT(solid, 150);
}

TEST(GasWalls, OutlinesWithVerticesOnTheCentreLinesAreCrossedOnce) {
  // A body's surface has a node at every boundary site, (k + 1/2) l0: with
  // the cell a multiple of l0 they fall on the lines through the cell
  // centres, where the division by the cell size can round either way.
  for (const double h : {0.0025, 0.001, 0.0005, 0.003}) {
    GasSolver<2> gas = uniform_box(40, 8, h, {1.2, {0, 0}, 1e5});
    std::vector<std::array<double, 2>> corners;
    const double x0 = 10 * h, x1 = 18 * h;
    for (int k = -2; k <= 10; ++k) corners.push_back({x1, (k + 0.5) * h});  // up the right face
    for (int k = 10; k >= -2; --k) corners.push_back({x0, (k + 0.5) * h});  // down the left face
    gas.set_walls(outline(corners));
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 40; ++i)
        EXPECT_EQ(gas.solid({i, j}), i >= 10 && i < 18) << "h " << h << ", cell " << i << ", " << j;
  }
}

TEST(GasWalls, GasAtRestRoundStillWallsStaysAtRestToTheBitAndPushesNoNetForce) {
  const GasPrimitive<2> air{1.2, {0, 0}, 101325};
  GasSolver<2> gas = uniform_box(50, 40, 0.002, air);
  const double c = std::cos(0.3), s = std::sin(0.3);
  std::vector<std::array<double, 2>> plate;  // thinner than a cell
  for (const auto& [x, y] :
       std::vector<std::array<double, 2>>{{-0.02, 0}, {0.02, 0}, {0.02, 0.0012}, {-0.02, 0.0012}})
    plate.push_back({0.05 + c * x - s * y, 0.03 + s * x + c * y});
  gas.set_walls(join(outline(plate), rectangle(0.004, 0.02, 0.01, 0.06)));
  EXPECT_GT(gas.closed_faces(), 40u);
  std::vector<std::vector<double>> before;
  for (int v = 0; v < 4; ++v) before.push_back(gas.conserved(v));
  for (int k = 0; k < 50; ++k) gas.advance(gas.stable_dt(0.8));
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 50; ++i) {
      if (gas.solid({i, j})) continue;
      const GasPrimitive<2> w = gas.primitive({i, j});
      ASSERT_EQ(w.rho, air.rho) << i << ", " << j;
      ASSERT_EQ(w.u[0], 0.0);
      ASSERT_EQ(w.u[1], 0.0);
      ASSERT_EQ(w.p, air.p);
    }
  // Each outline's faces come in pairs pushing either way.
  for (std::size_t body : {0u, 1u}) {
    double fx = 0, fy = 0;
    for (std::size_t k = 4 * body; k < 4 * body + 4; ++k) {
      fx += gas.wall_forces()[k][0] + gas.wall_forces()[k][2];
      fy += gas.wall_forces()[k][1] + gas.wall_forces()[k][3];
    }
    EXPECT_NEAR(fx, 0.0, 1e-9 * air.p * 0.002) << "body " << body;
    EXPECT_NEAR(fy, 0.0, 1e-9 * air.p * 0.002) << "body " << body;
  }
}

TEST(GasWalls, NoGasCrossesASlantedPlateThinnerThanACell) {
  // A plate a quarter of a cell thick across the whole box, high pressure
  // on its left: the mass on each side stays put.
  const double h = 0.004;
  GasSolver<2> gas = uniform_box(50, 30, h, {1.2, {0, 0}, 1e5});
  const double x_bottom = 0.08, x_top = 0.12, t = 0.25 * h;
  const auto midline = [&](double y) { return x_bottom + (x_top - x_bottom) * y / 0.12; };
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 50; ++i) {
      const auto x = gas.grid().centre({i, j});
      if (x[0] < midline(x[1])) gas.set({i, j}, {6.0, {0, 0}, 6e5});
    }
  gas.set_walls(outline({{midline(-0.05) - t / 2, -0.05},
                         {midline(-0.05) + t / 2, -0.05},
                         {midline(0.13) + t / 2, 0.13},
                         {midline(0.13) - t / 2, 0.13}}));
  const auto side_masses = [&] {
    std::array<double, 2> m{};
    for (int j = 0; j < 30; ++j)
      for (int i = 0; i < 50; ++i) {
        if (gas.solid({i, j})) continue;
        const auto x = gas.grid().centre({i, j});
        m[x[0] < midline(x[1]) ? 0 : 1] += gas.primitive({i, j}).rho * h * h;
      }
    return m;
  };
  const std::array<double, 2> before = side_masses();
  for (int k = 0; k < 300; ++k) gas.advance(gas.stable_dt(0.8));
  const std::array<double, 2> after = side_masses();
  EXPECT_NEAR(after[0], before[0], 1e-13 * before[0]);
  EXPECT_NEAR(after[1], before[1], 1e-13 * before[1]);
  // The plate is pushed to +x by about the pressure difference over its height.
  double fx = 0;
  for (const auto& f : gas.wall_forces()) fx += f[0] + f[2];
  EXPECT_GT(fx, 0.3 * 5e5 * 0.12);
}

// A tube along x one cell high, gas (rho0, 0, p0) right of a piston (a block
// from far left of the grid to x_p) moving at v; the walls reset every step.
struct PistonRun {
  double pressure_near_piston = 0;  // mean over cells 4-8 ahead of it
  // The gas's push on the piston against p* h after the first 50 steps:
  // the worst step's, and the impulse's.
  double worst_force = 0, impulse = 0;
  double exact = 0;
  double mass_error = 0, momentum_error = 0, energy_error = 0;  // of the balance, relative
};

PistonRun run_piston(double v, int n) {
  const double h = 1.0 / n, rho0 = 1.2, p0 = 101325;
  GasGrid<2> g;
  g.cells = {n, 1};
  g.h = h;
  GasSolver<2>::Boundaries b;
  b[0][1].kind = GasBoundaryKind::outflow;
  GasSolver<2> gas(g, kGamma, b);
  for (int i = 0; i < n; ++i) gas.set({i, 0}, {rho0, {0, 0}, p0});
  double x_p = 0.3, t = 0;
  const auto walls = [&] { return rectangle(-1.0, x_p, -1.0, 1.0, {v, 0}); };
  gas.set_walls(walls());
  const GasTotals<2> start = gas.totals();
  const double exact = ExactRiemann({rho0, 2 * v, p0}, {rho0, 0, p0}, kGamma).star_pressure();
  PistonRun r;
  double pushed_for = 0;
  for (int step = 0; t < 0.4 / 347.0; ++step) {
    const double dt = gas.stable_dt(0.8);
    gas.advance(dt);
    const double fx = gas.wall_forces()[1][0] + gas.wall_forces()[1][2];
    if (step >= 50) {
      r.worst_force = std::max(r.worst_force, std::abs(-fx / (exact * h) - 1));
      r.impulse += -fx * dt;
      pushed_for += dt;
    }
    t += dt;
    x_p += v * dt;
    gas.set_walls(walls());
  }
  const int first = static_cast<int>(std::floor(x_p / h + 0.5));
  for (int i = first + 4; i <= first + 8; ++i)
    r.pressure_near_piston += gas.primitive({i, 0}).p / 5;
  r.exact = exact;
  r.impulse = r.impulse / (exact * h * pushed_for) - 1;
  const GasTotals<2> end = gas.totals();
  const GasExchange<2>& x = gas.exchange();
  r.mass_error = (end.mass - start.mass - x.inflow.mass + x.lost.mass) / start.mass;
  r.momentum_error = (end.momentum[0] - start.momentum[0] - x.inflow.momentum[0] +
                      x.wall_impulse[0] + x.lost.momentum[0]) /
                     (p0 * t);
  r.energy_error =
      (end.energy - start.energy - x.inflow.energy + x.wall_work + x.lost.energy) / start.energy;
  return r;
}

TEST(GasWalls, APistonPushedInOrDrawnOutGivesTheExactPressureAndTheBalancesClose) {
  for (const double v : {120.0, -80.0})
    for (int n : {200, 800}) {
      const PistonRun r = run_piston(v, n);
      std::printf(
          "piston at %+.0f m/s, %d cells: p %.6g Pa (exact %.6g), force within %.2f %%, impulse "
          "%+.3f %%, balance errors %.1e %.1e %.1e\n",
          v, n, r.pressure_near_piston, r.exact, 100 * r.worst_force, 100 * r.impulse, r.mass_error,
          r.momentum_error, r.energy_error);
      EXPECT_NEAR(r.pressure_near_piston / r.exact, 1.0, 0.001) << v;
      // Each step's force jumps by a few per cent as the wall crosses a cell
      // centre; the impulse is exact to a few parts in ten thousand.
      EXPECT_LT(r.worst_force, 0.05) << v;
      EXPECT_LT(std::abs(r.impulse), 0.002) << v;
      EXPECT_LT(std::abs(r.mass_error), 1e-12);
      EXPECT_LT(std::abs(r.momentum_error), 1e-12);
      EXPECT_LT(std::abs(r.energy_error), 1e-12);
    }
}

TEST(GasWalls, AGapOpeningBetweenTwoBodiesStaysOutOfTheGasUntilGasReachesIt) {
  // Two blocks through the whole height touching at x = 0.1, gas beyond
  // x = 0.3. The left block steps back 15 mm: the cells in the gap have no
  // gas next to them and stay solid; then the right block steps back too
  // and the gas fills the gap.
  GasSolver<2> gas = uniform_box(40, 5, 0.01, {1.2, {0, 0}, 1e5});
  const auto walls = [&](double left_face, double right_end) {
    return join(rectangle(-1, left_face, -1, 2), rectangle(0.1, right_end, -1, 2));
  };
  gas.set_walls(walls(0.1, 0.3));
  const double mass = gas.totals().mass;
  gas.set_walls(walls(0.085, 0.3));
  for (int j = 0; j < 5; ++j) EXPECT_TRUE(gas.solid({9, j}));
  EXPECT_EQ(gas.totals().mass, mass);
  gas.advance(gas.stable_dt(0.8));
  EXPECT_NEAR(gas.totals().mass, mass, 1e-13 * mass);
  // The right block now starts at 0.115: its old cells from 0.1 to 0.115
  // and the gap join... still closed off from the gas beyond x = 0.3.
  gas.set_walls(join(rectangle(-1, 0.085, -1, 2), rectangle(0.115, 0.3, -1, 2)));
  for (int j = 0; j < 5; ++j) EXPECT_TRUE(gas.solid({9, j}) && gas.solid({10, j}));
  // Gone: the gas beyond x = 0.3 reaches the gap through the cells the
  // right block leaves, which the gas fills in turn.
  gas.set_walls(rectangle(-1, 0.085, -1, 2));
  for (int j = 0; j < 5; ++j)
    for (int i = 9; i < 40; ++i) EXPECT_FALSE(gas.solid({i, j})) << i << ", " << j;
  EXPECT_NEAR(gas.totals().mass, mass, 1e-13 * mass);
}

TEST(GasWalls, MovingWallsGiveTheSameBitsAt1To4Threads) {
  const int threads = thread_count();
  std::vector<std::vector<double>> first;
  for (int t = 1; t <= 4; ++t) {
    set_thread_count(t);
    GasSolver<2> gas = uniform_box(60, 40, 0.002, {1.2, {0, 0}, 1e5});
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 10; ++i) gas.set({i, j}, {2.0, {150, 0}, 2.5e5});
    double x = 0.05;
    for (int k = 0; k < 60; ++k) {
      gas.set_walls(join(rectangle(x, x + 0.004, 0.01, 0.07, {40, 0}),
                         outline({{0.1, 0.03}, {0.11, 0.035}, {0.1, 0.04}}, {0, -10})));
      const double dt = gas.stable_dt(0.8);
      gas.advance(dt);
      x += 40 * dt;
    }
    std::vector<std::vector<double>> fields;
    for (int v = 0; v < GasSolver<2>::kVars; ++v) fields.push_back(gas.conserved(v));
    if (t == 1)
      first = fields;
    else
      EXPECT_EQ(fields, first) << t << " threads";
  }
  set_thread_count(threads);
}

}  // namespace
}  // namespace mpsolid
