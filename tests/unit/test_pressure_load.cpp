// Pressure loads (src/core/loads.hpp on src/core/surface.hpp) in whole
// runs: the rod's plate under p = F / 60 mm against the step force F, free
// bodies under a uniform pressure through a large deformation (no net force
// or torque, energy balanced), the energy balance closing at O(dt), and
// the input checks.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

CaseSpec pressure_rod(const std::vector<std::string>& overrides = {}) {
  return load_case(testing::source_path("cases/shock_rod_pressure.toml"), overrides);
}

// The step-force run `force` and the pressure run `pressure` stepped side by
// side, `rows` times `steps` steps: the largest difference of any history
// column (the energies, momenta, angular momenta, the fastest speed, the
// plate's displacement and turn), each relative to its column's scale: its
// largest magnitude in the step-force run, or for the columns that stay at
// zero by symmetry, the x momentum's (a tenth of it for the angular
// momenta). In space with the z components and the plate's quaternion.
struct HistoryGap {
  double worst = 0;  // the largest relative difference
  double moved = 0;  // the plate's largest x displacement (m)
};
HistoryGap history_gap(Simulation& force, Simulation& pressure, int rows, std::int64_t steps) {
  HistoryGap gap;
  const bool space = force.spec().dimension == 3;
  double scale_px = 0, scale_ke = 0, scale_se = 0, scale_w = 0;
  for (int row = 0; row < rows; ++row) {
    force.advance(steps);
    pressure.advance(steps);
    const Diagnostics a = force.diagnostics(), b = pressure.diagnostics();
    const RigidBody &pa = force.state().rigid_bodies.at(0),
                    &pb = pressure.state().rigid_bodies.at(0);
    scale_px = std::max(scale_px, std::abs(a.momentum_x));
    gap.moved = std::max(gap.moved, std::abs(pa.xg - pa.xg0));
    scale_ke = std::max(scale_ke, a.kinetic_energy);
    scale_se = std::max(scale_se, a.strain_energy);
    scale_w = std::max(scale_w, a.external_work);
    std::vector<double> differences = {
        std::abs(a.kinetic_energy - b.kinetic_energy) / scale_ke,
        std::abs(a.strain_energy - b.strain_energy) / scale_se,
        std::abs(a.external_work - b.external_work) / scale_w,
        std::abs(a.momentum_x - b.momentum_x) / scale_px,
        std::abs(a.momentum_y - b.momentum_y) / scale_px,
        std::abs(a.angular_momentum - b.angular_momentum) / (scale_px * 0.1),
        std::abs(a.max_speed - b.max_speed) / a.max_speed,
        std::abs((pa.xg - pa.xg0) - (pb.xg - pb.xg0)) / gap.moved,
        std::abs((pa.yg - pa.yg0) - (pb.yg - pb.yg0)) / gap.moved,
        std::abs(pa.angle - pb.angle),
    };
    if (space) {
      differences.insert(differences.end(),
                         {std::abs(a.momentum_z - b.momentum_z) / scale_px,
                          std::abs(a.angular_momentum_x - b.angular_momentum_x) / (scale_px * 0.1),
                          std::abs(a.angular_momentum_y - b.angular_momentum_y) / (scale_px * 0.1),
                          std::abs((pa.zg - pa.zg0) - (pb.zg - pb.zg0)) / gap.moved});
      for (std::size_t k = 0; k < 4; ++k)
        differences.push_back(std::abs(pa.frame[k] - pb.frame[k]));
    }
    for (const double d : differences) gap.worst = std::max(gap.worst, d);
  }
  return gap;
}

// 20,000 steps of the paper's case: every history column of the pressure
// run within 1e-12 of the step force's.
TEST(PressureLoad, RodPlatePressureGivesTheStepForcesHistory) {
  Simulation force(testing::rod_case());
  Simulation pressure(pressure_rod());
  const HistoryGap gap = history_gap(force, pressure, 20, 1000);
  EXPECT_LT(gap.worst, 1e-12);
  EXPECT_GT(gap.moved, 1e-4);  // the plate moved: 0.26 mm
  const StepLoad& load = pressure.state().loads.at(0);
  EXPECT_TRUE(load.is_pressure());
  EXPECT_NEAR(load_work(pressure.particles(), load), pressure.diagnostics().external_work, 0.0);
}

// In space (cases/shock_rod_3d_pressure.toml against cases/shock_rod_3d.toml,
// at l0 = 2.5 mm, where the plate's loaded face lies 1 mm off the cells'):
// the pressure's net force on the rigid plate is the step force, so every
// history column and the plate's pose follow the step force's to 1e-12
// over 600 steps.
TEST(PressureLoad, RodPlatePressureInSpaceGivesTheStepForcesHistory) {
  Simulation force(load_case(testing::source_path("cases/shock_rod_3d.toml"), {"l0=0.0025"}));
  Simulation pressure(
      load_case(testing::source_path("cases/shock_rod_3d_pressure.toml"), {"l0=0.0025"}));
  const HistoryGap gap = history_gap(force, pressure, 6, 100);
  EXPECT_GT(gap.moved, 1e-5);
  EXPECT_LT(gap.worst, 1e-12);
}

// A free body under a uniform pressure on its whole surface, ramped up to
// `pressure`: its momentum and angular momentum stay at round-off however
// far it is squeezed, and the energy balance closes.
void expect_free_and_balanced(const std::string& body_toml, double pressure) {
  const std::string text = testing::rubber_case_head("squeezed", "finite_strain") + body_toml +
                           "[loads.squeeze]\ntype = \"pressure\"\nbody = \"body\"\npressure = " +
                           std::to_string(pressure) +
                           "\nhistory = \"ramp\"\nrise_time = 2e-4\n"
                           "[time]\ndt = 1e-6\nend = 1e-3\n[output]\nframe_interval = 1e-3\n";
  Simulation sim(load_case_text(text, "squeezed.toml"));
  const double l0 = sim.spec().l0;
  double peak_speed = 0;
  for (int k = 0; k < 6; ++k) {
    sim.advance(50);
    const Diagnostics d = sim.diagnostics();
    // The impulse scale: the pressure on the perimeter over the time so far.
    const double impulse = std::abs(pressure) * 0.08 * static_cast<double>(sim.step()) * 1e-6;
    EXPECT_LT(std::hypot(d.momentum_x, d.momentum_y), 1e-12 * impulse) << "step " << sim.step();
    EXPECT_LT(std::abs(d.angular_momentum), 1e-12 * impulse * 0.02) << "step " << sim.step();
    const double scale = std::max(std::abs(d.external_work), 1e-30);
    EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy - d.external_work), 0.02 * scale);
    peak_speed = std::max(peak_speed, d.max_speed);
  }
  // Squeezed hard: the surface moved by more than a particle spacing.
  const ParticleStore& p = sim.particles();
  double moved = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    moved = std::max(moved, std::hypot(p.x[i] - p.x0[i], p.y[i] - p.y0[i]));
  EXPECT_GT(moved, 0.5 * l0) << body_toml;
  EXPECT_GT(peak_speed, 0.0);
}

TEST(PressureLoad, UniformPressureLeavesAFreeBodyAtRest) {
  expect_free_and_balanced(
      "[bodies.body]\nkind = \"elastic\"\nmaterial = \"rubber\"\nshape = \"circle\"\n"
      "center = [0.001, -0.002]\nradius = 0.01\n",
      2e6);
  // Concave, with a hole, and turned: an L of 20 mm arms.
  expect_free_and_balanced(
      "[bodies.body]\nkind = \"elastic\"\nmaterial = \"rubber\"\nshape = \"polygon\"\n"
      "vertices = [[0.0, 0.0], [0.0, 0.02], [0.008, 0.02], [0.008, 0.008], [0.02, 0.008], "
      "[0.02, 0.0]]\nholes = [{ shape = \"circle\", center = [0.004, 0.004], radius = 0.002 }]\n",
      -1e6);
}

// In space: a pressure on a free box's left face (6 x 4 mm) pushes it along
// +x with the pressure times the face's area, however the face turns and
// stretches as the push runs into the box, and the box's symmetry keeps the
// other momenta and the angular momentum at round-off.
TEST(PressureLoad, APressureOnABoxsFaceInSpaceGivesItsImpulse) {
  for (const char* model : {"finite_strain", "paper"}) {
    const std::string text =
        fmt::format("name = \"pushed\"\nmodel = \"{}\"\ndimension = 3\nl0 = 0.001\n", model) +
        "[materials.rubber]\nE = 2.0e6\nnu = 0.3\nrho = 1000.0\n"
        "[bodies.box]\nkind = \"elastic\"\nmaterial = \"rubber\"\nx = [0.0, 0.01]\n"
        "y = [-0.003, 0.003]\nz = [-0.002, 0.002]\n"
        "[loads.push]\ntype = \"pressure\"\nbody = \"box\"\npressure = 1e4\nface = \"left\"\n"
        "[time]\ndt = \"auto\"\nend = 1e-3\n";
    Simulation sim(load_case_text(text, "pushed.toml"));
    sim.advance(400);
    const Diagnostics d = sim.diagnostics();
    // The face's area now, from its nodes at the next step's start.
    const double t = sim.time();
    sim.advance(1);
    const PressureSurface& face = sim.state().loads.at(0).surface;
    std::vector<double> ax(face.nodes(), 0.0), ay(face.nodes(), 0.0), az(face.nodes(), 0.0);
    add_node_area_vectors(face.quad, {face.x.data(), face.y.data(), face.z.data()}, 1.0,
                          {ax.data(), ay.data(), az.data()});
    double area = 0;
    for (const double a : ax) area -= a;
    const double area0 = 0.006 * 0.004, impulse = 1e4 * area0 * t;
    std::printf("%s: area %.6f of its start, momentum %.6f of p A0 t\n", model, area / area0,
                d.momentum_x / impulse);
    EXPECT_GT(d.momentum_x, impulse) << model;
    EXPECT_LT(d.momentum_x, impulse * area / area0) << model;
    EXPECT_LT(std::hypot(d.momentum_y, d.momentum_z), 1e-12 * impulse) << model;
    EXPECT_LT(std::hypot(d.angular_momentum_x, d.angular_momentum_y, d.angular_momentum),
              1e-12 * impulse * 0.01)
        << model;
    EXPECT_NEAR(d.external_work, d.kinetic_energy + d.strain_energy, 0.02 * d.external_work)
        << model;
  }
}

// The energy balance's gap KE + SE - W at the end of a blast wave on the
// disk halves with dt: the pressure's work is the integral of p v . n.
TEST(PressureLoad, EnergyBalanceClosesAtFirstOrderInDt) {
  const auto gap = [](double dt) {
    Simulation sim(load_case(testing::source_path("cases/disk_blast.toml"),
                             {"l0=0.001", fmt::format("time.dt={}", dt)}));
    sim.advance(static_cast<std::int64_t>(std::llround(1.5e-4 / dt)));
    const Diagnostics d = sim.diagnostics();
    return std::abs(d.kinetic_energy + d.strain_energy - d.external_work) / d.external_work;
  };
  const double coarse = gap(1e-6), fine = gap(5e-7), finer = gap(2.5e-7);
  EXPECT_LT(coarse, 0.05);
  EXPECT_GT(coarse / fine, 1.7) << coarse << " " << fine;
  EXPECT_GT(fine / finer, 1.7) << fine << " " << finer;
}

}  // namespace
}  // namespace mpsolid
