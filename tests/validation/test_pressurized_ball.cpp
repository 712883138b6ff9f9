// A free ball (radius R = 10 mm, nu = 0.3) squeezed by a uniform pressure on
// its whole surface, ramped up over 2 ms and damped to rest: in the plane a
// disk in plane strain, in space a sphere (the surface of
// src/core/surface3.hpp). The state is homogeneous, its radial stretch s
// exact. linear_elastic at p / E = 1e-3: s - 1 = -p (1 + nu)(1 - 2 nu) / E
// in the plane, -p (1 - 2 nu) / E in space. finite_strain at p / E = 0.1:
// the compressible neo-Hookean's Cauchy stress under F = s I in d
// dimensions, (mu (s^2 - 1) + d lambda ln s) / s^d = -p. Measured in the
// bulk (the particles' best uniform stretch) and at the loaded surface (the
// area or volume its nodes enclose, s^d of its start), at 5, 10 and 20
// particles across the disk's radius and 4, 8 and 16 across the sphere's.
// docs/verification.md has the figures.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "src/core/surface.hpp"
#include "src/core/surface3.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid {
namespace {

constexpr double kRadius = 0.010, kE = 2.8e6, kNu = 0.3;

std::string ball_case(int dimension, const std::string& model, double l0, double pressure) {
  const std::string ball =
      dimension == 3
          ? "dimension = 3\n[bodies.ball]\nshape = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\n"
          : "depth = 1.0\n[bodies.ball]\nshape = \"circle\"\ncenter = [0.0, 0.0]\n";
  return fmt::format(R"(name = "pressurized_ball"
model = "{model}"
l0 = {l0}
{ball}kind = "elastic"
material = "rubber"
radius = {r}
[materials.rubber]
E = {E}
nu = {nu}
rho = 1010.0
[loads.outside]
type = "pressure"
body = "ball"
pressure = {p}
history = "ramp"
rise_time = 0.002
[damping]
coefficient = 3000.0
end = 0.012
[time]
dt = "auto"
end = 0.012
[output]
frame_interval = 0.012
)",
                     fmt::arg("model", model), fmt::arg("l0", l0), fmt::arg("ball", ball),
                     fmt::arg("E", kE), fmt::arg("nu", kNu), fmt::arg("r", kRadius),
                     fmt::arg("p", pressure));
}

// The area (in space, the volume) the surface's nodes enclose, each node's
// position given by `position`: Point2 in the plane, x, y, z arrays in space.
template <class Position>
double enclosed_area(const PressureSurface& s, Position position) {
  double twice = 0;
  for (std::size_t k = 0; k < s.from.size(); ++k) {
    const Point2 a = position(s.from[k]), b = position(s.to[k]);
    twice += a.x * b.y - b.x * a.y;
  }
  return 0.5 * twice;
}

// Node k's position from the particles' coordinates `xs` (x, y[, z]).
std::vector<double> node_from(const PressureSurface& s, std::size_t k,
                              const std::vector<const std::vector<double>*>& xs) {
  std::vector<double> at(xs.size(), 0.0);
  for (std::uint32_t w = s.offsets[k]; w < s.offsets[k + 1]; ++w)
    for (std::size_t a = 0; a < xs.size(); ++a) at[a] += s.weight[w] * (*xs[a])[s.particle[w]];
  return at;
}

// The loaded surface's size now and at the start: its enclosed area in the
// plane, its enclosed volume in space.
double surface_ratio(const ParticleStore& p, const PressureSurface& s) {
  if (!s.in_space())
    return enclosed_area(s,
                         [&](std::size_t k) {
                           return Point2{s.x[k], s.y[k]};
                         }) /
           enclosed_area(s, [&](std::size_t k) {
             const std::vector<double> at = node_from(s, k, {&p.x0, &p.y0});
             return Point2{at[0], at[1]};
           });
  std::vector<double> x0, y0, z0;
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    const std::vector<double> at = node_from(s, k, {&p.x0, &p.y0, &p.z0});
    x0.push_back(at[0]);
    y0.push_back(at[1]);
    z0.push_back(at[2]);
  }
  return enclosed_volume(s.quad, {s.x.data(), s.y.data(), s.z.data()}, s.nodes()) /
         enclosed_volume(s.quad, {x0.data(), y0.data(), z0.data()}, s.nodes());
}

// The ball's radial strain at rest two ways: the bulk's (the particles'
// least-squares uniform stretch, sum u . X / sum |X|^2) and the loaded
// surface's (from the area or volume its nodes enclose).
struct Strains {
  double bulk, surface;
};
Strains measured_strains(int dimension, const std::string& model, double l0, double pressure) {
  Simulation sim(
      load_case_text(ball_case(dimension, model, l0, pressure), "pressurized_ball.toml"));
  sim.advance(sim.spec().step_count());
  const Diagnostics d = sim.diagnostics();
  EXPECT_LT(d.kinetic_energy, 1e-9 * d.strain_energy) << "not at rest";
  sim.advance(1);  // the nodes' positions are those at the start of the last step
  const ParticleStore& p = sim.state().particles;
  double ux = 0, xx = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    ux += (p.x[i] - p.x0[i]) * p.x0[i] + (p.y[i] - p.y0[i]) * p.y0[i];
    xx += p.x0[i] * p.x0[i] + p.y0[i] * p.y0[i];
    if (dimension == 3) {
      ux += (p.z[i] - p.z0[i]) * p.z0[i];
      xx += p.z0[i] * p.z0[i];
    }
  }
  const double ratio = surface_ratio(p, sim.state().loads.at(0).surface);
  return {ux / xx, std::pow(ratio, 1.0 / dimension) - 1};
}

// s with mu (s^2 - 1) + d lambda ln s = -p s^d, by Newton from s = 1.
double neo_hookean_stretch(int d, double pressure) {
  const double lambda = kE * kNu / ((1 + kNu) * (1 - 2 * kNu)), mu = kE / (2 * (1 + kNu));
  double s = 1;
  for (int k = 0; k < 50; ++k) {
    const double g = mu * (s * s - 1) + d * lambda * std::log(s) + pressure * std::pow(s, d);
    const double dg = 2 * mu * s + d * lambda / s + d * pressure * std::pow(s, d - 1);
    s -= g / dg;
  }
  return s;
}

// The errors against the exact stretch, linear_elastic then finite_strain,
// at `spacings`.
struct Model {
  std::string name;
  double pressure, exact;
};
std::vector<std::vector<Strains>> ball_errors(int dimension, const std::vector<double>& spacings) {
  const double small = 1e-3 * kE, large = 0.1 * kE;
  const double linear = small * (1 - 2 * kNu) / kE * (dimension == 3 ? 1.0 : 1 + kNu);
  std::vector<std::vector<Strains>> errors;
  for (const Model& m : {Model{"linear_elastic", small, 1 - linear},
                         Model{"finite_strain", large, neo_hookean_stretch(dimension, large)}}) {
    errors.emplace_back();
    for (const double l0 : spacings) {
      const Strains e = measured_strains(dimension, m.name, l0, m.pressure);
      errors.back().push_back({e.bulk / (m.exact - 1) - 1, e.surface / (m.exact - 1) - 1});
      std::printf("%dD %s, %g across the radius: radial strain %.5e, bulk %+.4f, surface %+.4f\n",
                  dimension, m.name.c_str(), kRadius / l0, m.exact - 1, errors.back().back().bulk,
                  errors.back().back().surface);
    }
  }
  return errors;
}

TEST(PressurizedBall, ADisksRadialStrainAtRestMatchesThePlaneStrainSolution) {
  for (const std::vector<Strains>& error : ball_errors(2, {0.002, 0.001, 0.0005})) {
    // The bulk within 0.5 % from 5 particles across (its error there is
    // the lattice circle's, not a trend); the surface, pressed into the
    // particles' outer row, within 2.5 % at 10 and converging.
    for (const Strains& e : error) EXPECT_LT(std::abs(e.bulk), 0.005);
    EXPECT_LT(std::abs(error[1].surface), 0.025);
    EXPECT_LT(std::abs(error[2].surface), 0.75 * std::abs(error[1].surface));
    EXPECT_LT(std::abs(error[1].surface), 0.75 * std::abs(error[0].surface));
  }
}

TEST(PressurizedBall, ASpheresRadialStrainAtRestMatchesTheExactSolution) {
  for (const std::vector<Strains>& error :
       ball_errors(3, {kRadius / 4, kRadius / 8, kRadius / 16})) {
    // The bulk within 2 % from 8 particles across and converging (10 % at
    // 4, where a sphere of 280 lattice sites is a rough one); the surface,
    // pressed into the particles' outer layer, within 4 % at 8 and
    // converging at about first order from there.
    EXPECT_LT(std::abs(error[1].bulk), 0.02);
    EXPECT_LT(std::abs(error[2].bulk), 0.25 * std::abs(error[1].bulk));
    EXPECT_LT(std::abs(error[1].surface), 0.04);
    EXPECT_LT(std::abs(error[2].surface), 0.65 * std::abs(error[1].surface));
  }
}

}  // namespace
}  // namespace mpsolid
