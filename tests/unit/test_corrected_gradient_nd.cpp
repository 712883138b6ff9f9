// The corrected-gradient oracle in any dimension: in 2D it gives the plane
// oracle's numbers; in 3D a homogeneous deformation is recovered exactly at
// every particle and leaves the interior force-free, a rigid turn is
// stress-free everywhere, and the forces are minus the energy's gradient
// (finite differences), the hourglass term included.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/bond_math.hpp"
#include "kernels/model_common.hpp"
#include "kernels/reference/corrected_gradient_nd.hpp"
#include "kernels/reference/reference_kernels.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

TEST(CorrectedGradientNd, In2DItGivesThePlaneOraclesNumbers) {
  Simulation sim(testing::rod_case({"model=finite_strain"}));
  ParticleStore& p = sim.state_to_change().particles;
  testing::jiggle(p, sim.spec().l0, 13, 0.0);  // finite_strain reads no rotation
  const BondTable& bonds = sim.state().bonds;
  const reference::GradientResult plane =
      reference::finite_strain_model(p, bonds, 1.0, /*consistent=*/true);
  reference::GradientState<2> s;
  const auto n = static_cast<Eigen::Index>(p.size());
  s.x.resize(2, n);
  s.x0.resize(2, n);
  s.bonds.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    s.x.col(static_cast<Eigen::Index>(i)) << p.x[i], p.y[i];
    s.x0.col(static_cast<Eigen::Index>(i)) << p.x0[i], p.y0[i];
    s.lambda.push_back(p.lambda[i]);
    s.mu.push_back(p.mu[i]);
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
      s.bonds[i].push_back(bonds.neighbor[b]);
  }
  s.re = bonds.geometry.re;
  s.n0 = number_density(bonds);
  s.volume = bonds.geometry.volume;
  const reference::GradientResultNd<2> any = reference::finite_strain_nd<2>(s, 1.0, true);
  EXPECT_NEAR(any.energy, plane.energy, 1e-13 * std::abs(plane.energy));
  const double scale = testing::max_abs(plane.fx);
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    ASSERT_NEAR(any.force(0, c), plane.fx[i], 1e-13 * scale) << i;
    ASSERT_NEAR(any.force(1, c), plane.fy[i], 1e-13 * scale) << i;
    for (int k = 0; k < 4; ++k)
      ASSERT_NEAR(any.def_grad[i](k / 2, k % 2), plane.def_grad[4 * i + k], 1e-14) << i;
  }
}

// An n^3 block of rubber particles at l0 = 1 mm, bonded within 2.1 l0.
reference::GradientState<3> block(int n) {
  const double l0 = 1e-3, re = 2.1 * l0;
  reference::GradientState<3> s;
  s.re = re;
  s.volume = l0 * l0 * l0;
  s.x0.resize(3, n * n * n);
  int k = 0;
  for (int c = 0; c < n; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) s.x0.col(k++) = l0 * Vector3d(a + 0.5, b + 0.5, c + 0.5);
  s.x = s.x0;
  s.lambda.assign(static_cast<std::size_t>(k), 2.8e7);
  s.mu.assign(static_cast<std::size_t>(k), 9.4e5);
  s.bonds.resize(static_cast<std::size_t>(k));
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      if (i != j && (s.x0.col(j) - s.x0.col(i)).norm() < re)
        s.bonds[static_cast<std::size_t>(i)].push_back(static_cast<std::size_t>(j));
  s.n0 = bond_math::lattice_number_density_3d(l0, re);
  return s;
}

TEST(CorrectedGradientNd, A3DHomogeneousDeformationIsRecoveredAndTheInteriorIsForceFree) {
  const int n = 10;
  reference::GradientState<3> s = block(n);
  Matrix3d f;
  f << 1.1, 0.05, 0.0, 0.02, 0.95, 0.03, 0.0, 0.04, 1.02;
  s.x = f * s.x0;
  const reference::GradientResultNd<3> r = reference::finite_strain_nd<3>(s, 1.0, true);
  const double stress = r.piola[0].cwiseAbs().maxCoeff();
  ASSERT_GT(stress, 0.0);
  int interior = 0;
  for (int c = 0; c < n; ++c)
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < n; ++a) {
        const auto i = static_cast<std::size_t>(a + n * (b + n * c));
        EXPECT_LT((r.def_grad[i] - f).cwiseAbs().maxCoeff(), 1e-12) << i;
        EXPECT_LT((r.piola[i] - r.piola[0]).cwiseAbs().maxCoeff(), 1e-9 * stress) << i;
        // Two neighbourhoods deep inside: every neighbour's own is full.
        const auto deep = [&](int v) { return v >= 4 && v <= n - 5; };
        if (deep(a) && deep(b) && deep(c)) {
          ++interior;
          EXPECT_LT(r.force.col(static_cast<Eigen::Index>(i)).norm(),
                    1e-9 * stress * s.volume / 1e-3)
              << i;
        }
      }
  EXPECT_EQ(interior, 8);
  // The surface is not force-free: the stress pulls on it.
  EXPECT_GT(testing::max_abs(r.force), 1e-3 * stress * s.volume / 1e-3);
}

TEST(CorrectedGradientNd, A3DRigidTurnIsStressFreeEverywhere) {
  reference::GradientState<3> s = block(6);
  const Matrix3d turn = Eigen::AngleAxisd(0.8, Vector3d(1.0, -0.3, 0.5).normalized()).matrix();
  s.x = turn * s.x0;
  s.x.colwise() += Vector3d(0.01, 0.02, -0.03);
  const reference::GradientResultNd<3> r = reference::finite_strain_nd<3>(s, 1.0, true);
  reference::GradientState<3> stretched = s;
  stretched.x = 1.01 * s.x0;
  const double scale = testing::max_abs(reference::finite_strain_nd<3>(stretched, 1.0, true).force);
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(testing::max_abs(r.force), 1e-9 * scale);
  EXPECT_NEAR(r.energy, 0.0, 1e-12);
}

TEST(CorrectedGradientNd, In3DTheForcesAreMinusTheEnergysGradient) {
  reference::GradientState<3> s = block(5);
  std::mt19937_64 rng(17);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (Eigen::Index i = 0; i < s.x.cols(); ++i)
    s.x.col(i) += 3e-5 * Vector3d(noise(rng), noise(rng), noise(rng));
  const reference::GradientResultNd<3> r = reference::finite_strain_nd<3>(s, 1.0, true);
  const double scale = testing::max_abs(r.force), h = 1e-9;
  for (const Eigen::Index i : {0, 31, 62, 124})
    for (int c = 0; c < 3; ++c) {
      reference::GradientState<3> plus = s, minus = s;
      plus.x(c, i) += h;
      minus.x(c, i) -= h;
      const double de = reference::finite_strain_nd<3>(plus, 1.0, true).energy -
                        reference::finite_strain_nd<3>(minus, 1.0, true).energy;
      EXPECT_NEAR(r.force(c, i), -de / (2 * h), 1e-5 * scale) << i << " " << c;
    }
}

}  // namespace
}  // namespace mpsolid
