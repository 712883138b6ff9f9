// The paper's model in 3D (the reference oracle for 3D kernels): a plane
// motion gives the 2D reference's strain, pressure, forces and torques to
// round-off; a rigid turn of a 3D block about any axis is stress-free; and
// on a randomly deformed and turned block the forces sum to zero and the
// torques with the forces' moments too (momentum and angular momentum
// kept); the mean rotation is symmetric and the mean angle for one axis.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/bond_math.hpp"
#include "kernels/model_common.hpp"
#include "kernels/reference/paper_model3.hpp"
#include "kernels/reference/reference_kernels.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

TEST(PaperModel3, TheMeanRotationIsSymmetricAndTheMeanAngleAboutOneAxis) {
  const Vector3d axis = Vector3d(0.3, -1.0, 0.4).normalized();
  const Quaterniond a(Eigen::AngleAxisd(0.9, axis)), b(Eigen::AngleAxisd(-0.5, axis));
  const Quaterniond ab = bond_math::mean_rotation(a, b), ba = bond_math::mean_rotation(b, a);
  EXPECT_LT(ab.angularDistance(ba), 1e-15);
  EXPECT_LT(ab.angularDistance(Quaterniond(Eigen::AngleAxisd(0.2, axis))), 1e-15);
  // q and -q are one orientation.
  Quaterniond minus_b;
  minus_b.coeffs() = -b.coeffs();
  EXPECT_LT(bond_math::mean_rotation(a, minus_b).angularDistance(ab), 1e-15);
}

TEST(PaperModel3, APlaneMotionGivesThe2DModel) {
  Simulation sim(testing::rod_case());
  ParticleStore& p = sim.state_to_change().particles;
  testing::jiggle(p, sim.spec().l0, 5, 0.4);
  const BondTable& bonds = sim.state().bonds;
  const reference::PaperResult plane = reference::paper_model(p, bonds);

  reference::PaperState3 s;
  const auto n = static_cast<Eigen::Index>(p.size());
  s.x.resize(3, n);
  s.x0.resize(3, n);
  s.mass.resize(n);
  s.lambda.resize(n);
  s.mu.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    s.x.col(i) = Vector3d(p.x[k], p.y[k], 0.0);
    s.x0.col(i) = Vector3d(p.x0[k], p.y0[k], 0.0);
    s.q.emplace_back(Eigen::AngleAxisd(p.theta[k], Vector3d::UnitZ()));
    s.mass[i] = 1.0 / p.inv_mass[k];
    s.lambda[i] = p.lambda[k];
    s.mu[i] = p.mu[k];
    for (std::uint32_t b = bonds.begin(k); b < bonds.end(k); ++b)
      if (bonds.neighbor[b] > k) s.bonds.emplace_back(k, bonds.neighbor[b]);
  }
  s.re = bonds.geometry.re;
  s.n0 = number_density(bonds);
  s.volume = bonds.geometry.volume;
  s.dimension = 2;
  const reference::PaperResult3 solid = reference::paper_model_3d(s);

  const double f_scale = testing::max_abs(plane.fx), t_scale = testing::max_abs(plane.torque);
  const double e_scale = testing::max_abs(plane.strain);
  ASSERT_GT(f_scale, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_NEAR(solid.strain[i], plane.strain[i], 1e-12 * e_scale) << i;
    ASSERT_NEAR(solid.pressure[i], plane.pressure[i], 1e-12 * testing::max_abs(plane.pressure));
  }
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    ASSERT_NEAR(solid.force(0, c), plane.fx[i], 1e-12 * f_scale) << i;
    ASSERT_NEAR(solid.force(1, c), plane.fy[i], 1e-12 * f_scale) << i;
    ASSERT_EQ(solid.force(2, c), 0.0) << i;
    ASSERT_NEAR(solid.torque(2, c), plane.torque[i], 1e-12 * t_scale) << i;
    ASSERT_NEAR(solid.torque(0, c), 0.0, 1e-12 * t_scale) << i;
    ASSERT_NEAR(solid.torque(1, c), 0.0, 1e-12 * t_scale) << i;
  }
}

// A 6 x 5 x 4 block of rubber particles at l0 = 1 mm, bonded within 2.1 l0.
reference::PaperState3 block() {
  const double l0 = 1e-3, re = 2.1 * l0;
  reference::PaperState3 s;
  s.re = re;
  s.volume = l0 * l0 * l0;
  s.dimension = 3;
  const int nx = 6, ny = 5, nz = 4, n = nx * ny * nz;
  s.x0.resize(3, n);
  int k = 0;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < ny; ++b)
      for (int a = 0; a < nx; ++a) s.x0.col(k++) = l0 * Vector3d(a + 0.5, b + 0.5, c + 0.5);
  s.x = s.x0;
  s.q.assign(static_cast<std::size_t>(n), Quaterniond::Identity());
  s.mass = Eigen::VectorXd::Constant(n, 1010.0 * s.volume);
  s.lambda = Eigen::VectorXd::Constant(n, 2.8e7);
  s.mu = Eigen::VectorXd::Constant(n, 9.4e5);
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if ((s.x0.col(j) - s.x0.col(i)).norm() < re)
        s.bonds.emplace_back(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
  s.n0 = bond_math::lattice_number_density_3d(l0, re);
  return s;
}

TEST(PaperModel3, ARigidTurnAboutAnyAxisIsStressFree) {
  reference::PaperState3 s = block();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  // The scale: a 1 % random deformation's forces.
  reference::PaperState3 deformed = s;
  for (Eigen::Index i = 0; i < s.x.cols(); ++i)
    deformed.x.col(i) += 1e-5 * Vector3d(noise(rng), noise(rng), noise(rng));
  const reference::PaperResult3 d = reference::paper_model_3d(deformed);
  const double f_scale = testing::max_abs(d.force), t_scale = testing::max_abs(d.torque);
  ASSERT_GT(f_scale, 0.0);
  ASSERT_GT(t_scale, 0.0);

  const Quaterniond turn(Eigen::AngleAxisd(1.1, Vector3d(0.2, 0.7, -0.4).normalized()));
  const Vector3d centre = s.x0.rowwise().mean(), shift(0.3, -0.2, 0.05);
  for (Eigen::Index i = 0; i < s.x.cols(); ++i) {
    s.x.col(i) = turn * (s.x0.col(i) - centre) + centre + shift;
    s.q[static_cast<std::size_t>(i)] = turn;
  }
  const reference::PaperResult3 r = reference::paper_model_3d(s);
  for (std::size_t i = 0; i < r.strain.size(); ++i) EXPECT_NEAR(r.strain[i], 0.0, 1e-12);
  EXPECT_LT(testing::max_abs(r.force), 1e-9 * f_scale);
  EXPECT_LT(testing::max_abs(r.torque), 1e-9 * t_scale);
}

TEST(PaperModel3, ForcesAndTorquesKeepMomentumAndAngularMomentum) {
  reference::PaperState3 s = block();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (Eigen::Index i = 0; i < s.x.cols(); ++i) {
    s.x.col(i) += 5e-5 * Vector3d(noise(rng), noise(rng), noise(rng));
    s.q[static_cast<std::size_t>(i)] =
        Quaterniond(Eigen::AngleAxisd(0.1 * noise(rng), Vector3d::Random().normalized()));
  }
  const reference::PaperResult3 r = reference::paper_model_3d(s);
  const double f_scale = testing::max_abs(r.force);
  Vector3d total = Vector3d::Zero(), moment = Vector3d::Zero();
  for (Eigen::Index i = 0; i < s.x.cols(); ++i) {
    total += r.force.col(i);
    moment += s.x.col(i).cross(r.force.col(i)) + r.torque.col(i);
  }
  EXPECT_LT(total.norm(), 1e-12 * f_scale * static_cast<double>(s.x.cols()));
  EXPECT_LT(moment.norm(), 1e-12 * f_scale * 0.01 * static_cast<double>(s.x.cols()));
  // Not trivially zero: the shear forces' torques are there.
  EXPECT_GT(testing::max_abs(r.torque), 1e-6 * f_scale * 1e-3);
}

}  // namespace
}  // namespace mpsolid
