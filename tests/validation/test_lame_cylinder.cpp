// Lame's thick cylinder in plane strain: a ring of inner radius a = 10 mm
// and outer radius b = 2a (nu = 0.3), its inner surface under a pressure p
// (p / E = 1e-3) ramped up over 2 ms and damped to rest. The inner wall's
// radial displacement (the pressure's surface nodes, which lie on r = a)
// against u(a) = (1 + nu) p a / (E (b^2 - a^2)) ((1 - 2 nu) a^2 + b^2), at
// 10, 20 and 40 particles across the wall, for linear_elastic and
// finite_strain, with their default hourglass penalty and with three times
// it. docs/verification.md has the figures at more spacings: the
// error scatters by about +-1 % with how the circle falls on the lattice
// (the material in the wall's first layer) around its fall with l0.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid {
namespace {

constexpr double kA = 0.010, kB = 0.020, kE = 2.8e6, kNu = 0.3, kP = 2800.0;

std::string lame_case(const std::string& model, double l0, double hourglass) {
  return fmt::format(R"(name = "lame"
model = "{model}"
l0 = {l0}
depth = 1.0
[materials.rubber]
E = {E}
nu = {nu}
rho = 1010.0
[bodies.ring]
kind = "elastic"
material = "rubber"
shape = "annulus"
center = [0.0, 0.0]
radii = [{a}, {b}]
[loads.inside]
type = "pressure"
body = "ring"
pressure = {p}
box = {{ x = [-0.0105, 0.0105], y = [-0.0105, 0.0105] }}
history = "ramp"
rise_time = 0.002
[{model}]
hourglass = {hourglass}
[damping]
coefficient = 3000.0
end = 0.012
[time]
dt = "auto"
end = 0.012
[output]
frame_interval = 0.012
)",
                     fmt::arg("model", model), fmt::arg("l0", l0), fmt::arg("hourglass", hourglass),
                     fmt::arg("E", kE), fmt::arg("nu", kNu), fmt::arg("a", kA), fmt::arg("b", kB),
                     fmt::arg("p", kP));
}

// The inner wall's mean radial displacement over the relative error of Lame's.
double inner_wall_error(const std::string& model, double l0, double hourglass = 1.0) {
  Simulation sim(load_case_text(lame_case(model, l0, hourglass), "lame.toml"));
  sim.advance(sim.spec().step_count());
  const Diagnostics d = sim.diagnostics();
  EXPECT_LT(d.kinetic_energy, 1e-9 * d.strain_energy) << "not at rest";
  EXPECT_LT(std::abs(d.strain_energy + d.damping_loss - d.external_work), 0.01 * d.external_work);
  sim.advance(1);  // the nodes' positions are those at the start of the last step
  const PressureSurface& s = sim.state().loads.at(0).surface;
  double sum = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) sum += std::hypot(s.x[k], s.y[k]) - kA;
  const double u = sum / static_cast<double>(s.nodes());
  const double exact =
      (1 + kNu) * kP * kA / (kE * (kB * kB - kA * kA)) * ((1 - 2 * kNu) * kA * kA + kB * kB);
  return u / exact - 1;
}

TEST(LameCylinder, InnerWallDisplacementConvergesToThePlaneStrainSolution) {
  for (const std::string model : {"linear_elastic", "finite_strain"}) {
    SCOPED_TRACE(model);
    const double at10 = inner_wall_error(model, 0.001), at20 = inner_wall_error(model, 0.0005),
                 at40 = inner_wall_error(model, 0.00025);
    std::printf("%s: %+.4f, %+.4f, %+.4f at 10, 20, 40 across\n", model.c_str(), at10, at20, at40);
    // 2.5-2.6 %, 2.1 % and 0.7-0.8 %: the 2 % at 10 across is not reached
    // (docs/verification.md says why).
    EXPECT_LT(std::abs(at10), 0.03);
    EXPECT_LT(std::abs(at20), 0.025);
    EXPECT_LT(std::abs(at40), 0.01);
    EXPECT_GT(std::abs(at10) / std::abs(at40), 2.0);  // falling with l0
  }
}

// A stiffer hourglass penalty holds the near-surface modes better, at a
// smaller time step (7.6 -> 5.4 us here): 1.6-1.7 % at 10 and 20 across.
TEST(LameCylinder, WithThreeTimesTheHourglassPenaltyTheWallIsWithinTwoPercent) {
  for (const std::string model : {"linear_elastic", "finite_strain"}) {
    SCOPED_TRACE(model);
    const double at10 = inner_wall_error(model, 0.001, 3.0),
                 at20 = inner_wall_error(model, 0.0005, 3.0);
    std::printf("%s, hourglass 3: %+.4f, %+.4f at 10, 20 across\n", model.c_str(), at10, at20);
    EXPECT_LT(std::abs(at10), 0.02);
    EXPECT_LT(std::abs(at20), 0.02);
  }
}

}  // namespace
}  // namespace mpsolid
