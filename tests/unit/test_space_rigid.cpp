// Rigid bodies in space through the product's path: a brick's inertia
// against the lattice's sums, the intermediate-axis flip against Euler's
// equations integrated apart (second order in dt, the angular momentum
// vector kept to round-off), a driven body following its motion exactly
// with the energy balance closed, a rigid sphere striking an elastic one
// (momenta kept, the body exactly rigid), and the same bits at 1-4 threads.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

Eigen::Quaterniond quaternion(const std::array<double, 4>& q) {
  return {q[0], q[1], q[2], q[3]};
}

CaseSpec brick(const std::vector<std::string>& overrides = {}) {
  return load_case(testing::source_path("cases/tumbling_brick.toml"), overrides);
}

// The brick of 4 x 8 x 12 particles: its principal moments are the
// lattice's sums, M l0^2 ((n_a^2 - 1) + (n_b^2 - 1)) / 12, ascending (about
// z, y, x), with the particles' spins N m l0^2 / 6 beside them.
TEST(SpaceRigid, BrickInertiaIsTheLatticeSums) {
  const CaseSpec spec = brick();
  Simulation sim(spec);
  const RigidBody& b = sim.state().rigid_bodies.at(0);
  ASSERT_EQ(b.range.size(), 384u);
  const double l0 = spec.l0, m = 7850.0 * l0 * l0 * l0, mass = 384 * m;
  EXPECT_NEAR(b.mass_total, mass, 1e-14 * mass);
  const double scale = mass * l0 * l0 / 12.0;
  const double expected[3] = {scale * (15 + 63), scale * (15 + 143), scale * (63 + 143)};
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(b.orbital_moments[a], expected[a], 1e-12 * expected[2]) << a;
  EXPECT_NEAR(b.spin_inertia, 384 * m * l0 * l0 / 6.0, 1e-12 * b.spin_inertia);
  const Eigen::Matrix3d axes = quaternion(b.axes).toRotationMatrix();
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(std::abs(axes.col(a).dot(Eigen::Vector3d::Unit(2 - a))), 1.0, 1e-12) << a;
  EXPECT_NEAR(b.xg, 0.0, 1e-15);
  EXPECT_NEAR(b.zg, 0.0, 1e-15);
}

// Euler's equations of a torque-free body in its principal frame,
// I1 w1' = (I2 - I3) w2 w3 and its cycles, by classical Runge-Kutta.
Eigen::Vector3d euler_rates(const Eigen::Vector3d& w, const Eigen::Vector3d& moments) {
  return {(moments[1] - moments[2]) * w[1] * w[2] / moments[0],
          (moments[2] - moments[0]) * w[2] * w[0] / moments[1],
          (moments[0] - moments[1]) * w[0] * w[1] / moments[2]};
}
Eigen::Vector3d rk4(Eigen::Vector3d w, const Eigen::Vector3d& moments, double h, int steps) {
  for (int k = 0; k < steps; ++k) {
    const Eigen::Vector3d a = euler_rates(w, moments);
    const Eigen::Vector3d b = euler_rates(w + 0.5 * h * a, moments);
    const Eigen::Vector3d c = euler_rates(w + 0.5 * h * b, moments);
    const Eigen::Vector3d d = euler_rates(w + h * c, moments);
    w += h / 6.0 * (a + 2.0 * b + 2.0 * c + d);
  }
  return w;
}

struct Flip {
  double rate_error = 0;          // max |w_body - w_reference| / |w0| over the samples
  double momentum_error = 0;      // max |L - L0| / |L0|
  double energy_error = 0;        // max |KE / KE0 - 1|
  double least_intermediate = 1;  // min of w_2(t) / w_2(0) in the body frame
};

// The brick to t = 3 s (its first flip near 1.7 s) at dt, sampled every
// 0.1 s against the reference at dt / 20.
Flip tumble(double dt) {
  Simulation sim(brick({"time.dt=" + std::to_string(dt)}));
  const RigidBody& start = sim.state().rigid_bodies.at(0);
  const Eigen::Vector3d moments =
      Eigen::Vector3d(start.orbital_moments[0], start.orbital_moments[1],
                      start.orbital_moments[2])
          .array() +
      start.spin_inertia;  // the paper's model: particles spin too
  // (state() brings the threads' parts back first.)
  const auto body_rate = [&] {
    const RigidBody& b = sim.state().rigid_bodies.at(0);
    return Eigen::Vector3d(quaternion(b.frame).conjugate() *
                           Eigen::Vector3d(b.omega_x, b.omega_y, b.omega));
  };
  const Diagnostics d0 = sim.diagnostics();
  const Eigen::Vector3d l0(d0.angular_momentum_x, d0.angular_momentum_y, d0.angular_momentum);
  Eigen::Vector3d reference = body_rate();
  const double w2 = reference[1];
  const auto per_sample = static_cast<std::int64_t>(std::lround(0.1 / dt));
  Flip out;
  for (int sample = 0; sample < 30; ++sample) {
    sim.advance(per_sample);
    reference = rk4(reference, moments, dt / 20, static_cast<int>(20 * per_sample));
    const Eigen::Vector3d w = body_rate();
    const Diagnostics d = sim.diagnostics();
    const Eigen::Vector3d l(d.angular_momentum_x, d.angular_momentum_y, d.angular_momentum);
    out.rate_error = std::max(out.rate_error, (w - reference).norm() / std::abs(w2));
    out.momentum_error = std::max(out.momentum_error, (l - l0).norm() / l0.norm());
    out.energy_error =
        std::max(out.energy_error, std::abs(d.kinetic_energy / d0.kinetic_energy - 1));
    out.least_intermediate = std::min(out.least_intermediate, w[1] / w2);
  }
  return out;
}

TEST(SpaceRigid, IntermediateAxisFlipsAsEulersEquationsSay) {
  const Flip coarse = tumble(1e-3), fine = tumble(5e-4);
  for (const Flip& f : {coarse, fine}) {
    EXPECT_LT(f.least_intermediate, -0.99);  // it flipped over
    EXPECT_LT(f.momentum_error, 1e-13);      // measured 4e-15 over 6,000 steps
    EXPECT_LT(f.energy_error, 1e-5);
  }
  EXPECT_LT(coarse.rate_error, 3e-5);  // measured 7.2e-6
  const double order = std::log2(coarse.rate_error / fine.rate_error);
  EXPECT_GT(order, 1.8) << coarse.rate_error << " vs " << fine.rate_error;
  EXPECT_LT(order, 2.2) << coarse.rate_error << " vs " << fine.rate_error;
}

// A rubber block glued to a paddle driven along z and spun about z: the
// paddle's pose is its motion's, exactly; its particles sit at the pose;
// the driver's work is the kinetic and strain energy it gave.
const std::string kPaddle = R"(
name = "paddle"
model = "finite_strain"
dimension = 3
l0 = 0.001

[materials.rubber]
E = 2.0e6
nu = 0.4
rho = 1000.0

[bodies.paddle]
kind = "rigid"
material = "rubber"
x = [-0.003, 0.003]
y = [-0.003, 0.003]
z = [0.0, 0.002]

[bodies.paddle.motion]
velocity = [0.0, 0.0, 0.5]
spin = [0.0, 0.0, 20.0]

[bodies.block]
kind = "elastic"
material = "rubber"
x = [-0.003, 0.003]
y = [-0.003, 0.003]
z = [0.002, 0.008]

[time]
dt = 1e-6
end = 1e-3
)";

TEST(SpaceRigid, ADrivenBodyFollowsItsMotionAndTheBalanceCloses) {
  Simulation sim(load_case_text(kPaddle, "paddle.toml"));
  const int steps = 2000;
  sim.advance(steps);
  const RigidBody& b = sim.state().rigid_bodies.at(0);
  const double t = steps * 1e-6;
  EXPECT_NEAR(b.zg - b.zg0, 0.5 * t, 1e-15);
  EXPECT_EQ(b.xg, b.xg0);
  const Eigen::Quaterniond turn = quaternion(rotation_from_start(b));
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(20.0 * t, Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(turn.angularDistance(expected), 0.0, 1e-12);
  const ParticleStore& p = sim.particles();
  const Eigen::Matrix3d r = turn.toRotationMatrix();
  double placed = 0;
  for (std::size_t i = b.range.begin; i < b.range.end; ++i) {
    const std::size_t k = i - b.range.begin;
    const Eigen::Vector3d x =
        Eigen::Vector3d(b.xg, b.yg, b.zg) + r * Eigen::Vector3d(b.dx0[k], b.dy0[k], b.dz0[k]);
    placed = std::max(placed, (x - Eigen::Vector3d(p.x[i], p.y[i], p.z[i])).norm());
  }
  EXPECT_LT(placed, 1e-17);
  const Diagnostics d = sim.diagnostics();
  EXPECT_GT(b.work, 0.0);
  EXPECT_NEAR(d.external_work, b.work, 1e-15 * b.work);
  EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy - b.work), 2e-3 * b.work)
      << d.kinetic_energy << " + " << d.strain_energy << " vs " << b.work;
}

// The struck sphere of cases/colliding_spheres.toml made rigid: momenta
// kept through the contact, the rigid sphere's particles where its pose
// puts them, and it leaves spinning.
TEST(SpaceRigid, ARigidSphereStruckObliquelyKeepsTheMomenta) {
  Simulation sim(load_case(testing::source_path("cases/colliding_spheres.toml"),
                           {"bodies.b.kind=\"rigid\"", "l0=0.004"}));
  const Diagnostics d0 = sim.diagnostics();
  const double scale = std::abs(d0.momentum_x);
  const RigidBody& b = sim.state().rigid_bodies.at(0);
  const double lever = 0.01 * scale;  // the momentum scale times the sphere's radius
  sim.advance(static_cast<std::int64_t>(std::lround(0.002 / sim.spec().dt)));
  const Diagnostics d = sim.diagnostics();
  EXPECT_NEAR(d.momentum_x, d0.momentum_x, 1e-13 * scale);
  EXPECT_NEAR(d.momentum_y, d0.momentum_y, 1e-13 * scale);
  EXPECT_NEAR(d.momentum_z, d0.momentum_z, 1e-13 * scale);
  EXPECT_NEAR(d.angular_momentum_x, d0.angular_momentum_x, 1e-13 * lever);
  EXPECT_NEAR(d.angular_momentum_y, d0.angular_momentum_y, 1e-13 * lever);
  EXPECT_NEAR(d.angular_momentum, d0.angular_momentum, 1e-13 * lever);
  EXPECT_GT(b.vx, 1.0);                                       // struck, it leaves along +x
  EXPECT_GT(std::hypot(b.omega_x, b.omega_y, b.omega), 1.0);  // and spins
  // Every distance within the rigid sphere is its initial one.
  const ParticleStore& p = sim.particles();
  double drift = 0;
  for (std::size_t i = b.range.begin; i < b.range.end; i += 7)
    for (std::size_t j = i + 1; j < b.range.end; j += 5) {
      const double now = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]);
      const double then = std::hypot(p.x0[i] - p.x0[j], p.y0[i] - p.y0[j], p.z0[i] - p.z0[j]);
      drift = std::max(drift, std::abs(now - then));
    }
  EXPECT_LT(drift, 1e-16);
  EXPECT_LT(std::abs(d.kinetic_energy + d.strain_energy + d.contact_energy - d0.kinetic_energy) /
                d0.kinetic_energy,
            5e-3);  // measured 4e-4
}

TEST(SpaceRigid, SameBitsAt1To4Threads) {
  const std::vector<CaseSpec> cases = {
      brick({"time.dt=1e-3"}), load_case_text(kPaddle, "paddle.toml"),
      load_case(testing::source_path("cases/colliding_spheres.toml"),
                {"bodies.b.kind=\"rigid\"", "l0=0.004", "model=\"paper\""})};
  for (const CaseSpec& spec : cases) {
    ParticleStore one;
    std::vector<double> pose;
    for (const int threads : {1, 2, 3, 4}) {
      set_thread_count(threads);
      Simulation sim(spec);
      sim.advance(300);
      const RigidBody& b = sim.state().rigid_bodies.at(0);
      std::vector<double> now = pose_values(b);
      now.push_back(b.work);  // the pose and the driver's work
      if (threads == 1) {
        one = sim.particles();
        pose = now;
        continue;
      }
      EXPECT_TRUE(testing::same_bits(one, sim.particles())) << spec.name << ", " << threads;
      EXPECT_TRUE(testing::same_bits(pose, now)) << spec.name << ", " << threads;
    }
  }
  set_thread_count(available_cores());
}

}  // namespace
}  // namespace mpsolid
