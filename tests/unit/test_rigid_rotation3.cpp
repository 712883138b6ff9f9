// A rigid body's 3D rotation against plain references: the principal axes
// of a box of particles against its moments in closed form; a spin about a
// principal axis at exactly L / I; a free body against Euler's equations
// integrated by RK4 at a small step (second order in dt); and a body spun
// about its intermediate axis, which flips, its angular momentum in the
// world kept to round-off and its energy error bounded over many flips.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "src/core/rigid_rotation3.hpp"

namespace mpsolid {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

TEST(RigidRotation3, PrincipalAxesOfABoxOfParticles) {
  // 6 x 4 x 2 particles of mass 1, spacing 1, turned by a known rotation.
  const Quaterniond turn(Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized()));
  Eigen::Matrix3Xd x(3, 48);
  Eigen::VectorXd m = Eigen::VectorXd::Ones(48), spin = Eigen::VectorXd::Constant(48, 1.0 / 6);
  int n = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 6; ++i) x.col(n++) = turn * Vector3d(i - 2.5, j - 1.5, k - 0.5);
  const PrincipalAxes p = principal_axes(inertia_tensor(x, m, Vector3d::Zero(), spin));
  // A solid box's moments, m (b^2 + c^2) / 12 with the particles' own spin,
  // sums of the lattice's squares exactly: 48 / 12 (a^2 - 1) per axis plus N / 6.
  const auto lattice = [](double a) { return 48.0 / 12 * (a * a - 1); };
  const Vector3d expected(lattice(2) + lattice(4) + 8, lattice(2) + lattice(6) + 8,
                          lattice(4) + lattice(6) + 8);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(p.moments[a], expected[a], 1e-12 * expected[a]);
  EXPECT_NEAR(p.axes.determinant(), 1.0, 1e-14);
  // The axes are the turned box's: the longest side (x) has the smallest moment.
  EXPECT_NEAR(std::abs(p.axes.col(0).dot(turn * Vector3d::UnitX())), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.axes.col(2).dot(turn * Vector3d::UnitZ())), 1.0, 1e-12);
}

TEST(RigidRotation3, ASpinAboutAPrincipalAxisTurnsAtLOverI) {
  const Vector3d moments(1.0, 2.0, 3.0);
  for (int a = 0; a < 3; ++a) {
    Quaterniond q = Quaterniond::Identity();
    Vector3d pi = 0.6 * Vector3d::Unit(a);
    const double dt = 1e-3;
    for (int k = 0; k < 1000; ++k) rotate_free(q, pi, moments, dt);
    const Eigen::AngleAxisd turned(q);
    const double expected = std::remainder(0.6 / moments[a] * 1.0, 2 * std::numbers::pi);
    EXPECT_NEAR(turned.angle() * turned.axis().dot(Vector3d::Unit(a)), expected, 1e-12);
    EXPECT_NEAR((pi - 0.6 * Vector3d::Unit(a)).norm(), 0.0, 1e-15);
  }
}

// Euler's equations in the body frame, dPi/dt = Pi x (I^-1 Pi), with the
// orientation dq/dt = q (0, w) / 2, by RK4.
void euler_rk4(Quaterniond& q, Vector3d& pi, const Vector3d& moments, double dt) {
  const auto f = [&](const Quaterniond& qq, const Vector3d& p, Quaterniond& dq, Vector3d& dp) {
    const Vector3d w = p.cwiseQuotient(moments);
    dp = p.cross(w);
    const Quaterniond qw = qq * Quaterniond(0, w.x(), w.y(), w.z());
    dq.coeffs() = 0.5 * qw.coeffs();
  };
  Quaterniond k1, k2, k3, k4, t;
  Vector3d p1, p2, p3, p4;
  f(q, pi, k1, p1);
  t.coeffs() = q.coeffs() + 0.5 * dt * k1.coeffs();
  f(t, pi + 0.5 * dt * p1, k2, p2);
  t.coeffs() = q.coeffs() + 0.5 * dt * k2.coeffs();
  f(t, pi + 0.5 * dt * p2, k3, p3);
  t.coeffs() = q.coeffs() + dt * k3.coeffs();
  f(t, pi + dt * p3, k4, p4);
  q.coeffs() += dt / 6 * (k1.coeffs() + 2 * k2.coeffs() + 2 * k3.coeffs() + k4.coeffs());
  pi += dt / 6 * (p1 + 2 * p2 + 2 * p3 + p4);
  q.normalize();
}

// The world angular momentum and the orientation's error after time T at
// step dt, against RK4 at a step a thousand times smaller.
double orientation_error(double dt) {
  const Vector3d moments(1.0, 2.0, 3.0), start(0.3, 0.8, -0.5);
  const double end = 2.0;
  Quaterniond q = Quaterniond::Identity(), qr = q;
  Vector3d pi = start, pr = start;
  const int n = static_cast<int>(std::lround(end / dt));
  for (int k = 0; k < n; ++k) rotate_free(q, pi, moments, dt);
  const int nr = 200000;
  for (int k = 0; k < nr; ++k) euler_rk4(qr, pr, moments, end / nr);
  return q.angularDistance(qr);
}

TEST(RigidRotation3, AFreeBodyFollowsEulersEquationsAtSecondOrder) {
  const double e1 = orientation_error(0.02), e2 = orientation_error(0.01),
               e3 = orientation_error(0.005);
  std::printf("orientation error at dt 0.02 / 0.01 / 0.005: %.3e %.3e %.3e (orders %.2f %.2f)\n",
              e1, e2, e3, std::log2(e1 / e2), std::log2(e2 / e3));
  EXPECT_LT(e3, 1e-3);
  EXPECT_NEAR(std::log2(e1 / e2), 2.0, 0.2);
  EXPECT_NEAR(std::log2(e2 / e3), 2.0, 0.2);
}

TEST(RigidRotation3, ABodySpunAboutItsIntermediateAxisFlipsKeepingItsMomentum) {
  const Vector3d moments(1.0, 2.0, 3.0);
  Quaterniond q = Quaterniond::Identity();
  Vector3d pi(1e-3, 2.0, 1e-3);  // about the intermediate axis, nudged
  const Vector3d world = q * pi;
  const double energy = 0.5 * pi.dot(pi.cwiseQuotient(moments)), dt = 1e-3;
  int flips = 0;
  double sign = 1, worst_l = 0, worst_e_first = 0, worst_e_last = 0;
  const int steps = 200000;  // t = 200, about 10 flips
  for (int k = 0; k < steps; ++k) {
    rotate_free(q, pi, moments, dt);
    // The body's intermediate axis in the world, against the fixed L.
    const double along = (q * Vector3d::UnitY()).dot(world);
    if (along * sign < 0) {
      ++flips;
      sign = -sign;
    }
    worst_l = std::max(worst_l, (q * pi - world).norm() / world.norm());
    const double e = std::abs(0.5 * pi.dot(pi.cwiseQuotient(moments)) / energy - 1);
    (k < steps / 10 ? worst_e_first : worst_e_last) =
        std::max(k < steps / 10 ? worst_e_first : worst_e_last, e);
  }
  std::printf(
      "intermediate axis: %d flips in t = 200, |L - L0| / |L| <= %.1e, energy error %.1e (first "
      "tenth) %.1e (rest)\n",
      flips, worst_l, worst_e_first, worst_e_last);
  EXPECT_GE(flips, 4);
  EXPECT_LT(worst_l, 1e-11);  // round-off over 200,000 steps (1e-16 a step, a random walk)
  EXPECT_LT(worst_e_last, 1e-4);
  EXPECT_LT(worst_e_last, 2 * worst_e_first + 1e-12);  // bounded: no drift over the flips
}

}  // namespace
}  // namespace mpsolid
