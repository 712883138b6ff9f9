// The energy-consistent and finite-strain models against plain references,
// and the invariants every model must keep: rigid motion is force-free,
// momenta are conserved, and (for the consistent models) energy too.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "kernels/finite_strain_model.hpp"
#include "kernels/paper_model.hpp"
#include "kernels/reference/reference_kernels.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using testing::jiggle;

TEST(PaperConservative, KernelsMatchThePlainReference) {
  Simulation sim(testing::rod_case({"model=paper_conservative"}));
  ParticleStore& p = sim.state_to_change().particles;
  jiggle(p, sim.spec().l0, 9, 0.4);
  sim.refresh_fields();
  testing::run_model_passes<PaperConservativeModel>(p, sim.state().bonds);
  const auto ref = reference::paper_model(p, sim.state().bonds, true);
  const auto plain = reference::paper_model(p, sim.state().bonds, false);
  const double fscale = testing::max_abs(ref.fx), tscale = testing::max_abs(ref.torque);
  double extra = 0;  // how much the consistent terms change the force
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    ASSERT_NEAR(p.fx[i], ref.fx[i], 1e-11 * fscale) << i;
    ASSERT_NEAR(p.fy[i], ref.fy[i], 1e-11 * fscale) << i;
    ASSERT_NEAR(p.torque[i], ref.torque[i], 1e-11 * tscale) << i;
    extra = std::max(extra, std::abs(ref.fx[i] - plain.fx[i]));
  }
  EXPECT_GT(extra, 1e-4 * fscale);  // the comparison is not vacuous
}

// Affine deformation: kernel correction makes F exact at every particle,
// surfaces included, and the stress follows the neo-Hookean law.
TEST(FiniteStrain, AffineDeformationGivesExactGradientEverywhere) {
  Simulation sim(testing::free_block_case(12, 11, false, 1e-7, "finite_strain"));
  ParticleStore& p = sim.state_to_change().particles;
  Eigen::Matrix2d f;
  f << 1.08, 0.21, -0.13, 0.87;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.x[i] = 0.3 + f(0, 0) * p.x0[i] + f(0, 1) * p.y0[i];
    p.y[i] = -0.1 + f(1, 0) * p.x0[i] + f(1, 1) * p.y0[i];
  }
  FiniteStrainModel model(p, sim.state().bonds, default_options(FiniteStrainModel::options()));
  model.compute_strain(p, sim.state().bonds, p.all());
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 4; ++k)
      ASSERT_NEAR(model.deformation_gradient()[4 * i + static_cast<std::size_t>(k)],
                  f(k / 2, k % 2), 1e-12)
          << "particle " << i;
    EXPECT_NEAR(model.jacobian()[i], f.determinant(), 1e-12);
    EXPECT_NEAR(p.strain[i], std::log(f.determinant()), 1e-12);
    EXPECT_NEAR(p.pressure[i], -p.lambda[i] * std::log(f.determinant()) / f.determinant(),
                1e-9 * p.lambda[i]);
  }
  // A particle whose neighbours all have full neighbourhoods (4 l0 from every
  // surface) feels no net force under a homogeneous stress; a surface
  // particle does.
  model.compute_forces(p, sim.state().bonds, p.moving());
  const double scale = p.mu[0] * sim.spec().l0 * sim.spec().depth;  // force at unit strain
  const double l0 = sim.spec().l0;
  EXPECT_EQ(testing::expect_interior_force_free(p, l0, 1e-9 * scale), 12);
  EXPECT_GT(std::hypot(p.fx[0], p.fy[0]), 1e-3 * scale);
}

class FiniteStrainForms : public ::testing::TestWithParam<bool> {};

TEST_P(FiniteStrainForms, KernelsMatchThePlainReference) {
  const bool consistent = GetParam();
  Simulation sim(testing::rod_case({"model=finite_strain"}));
  ParticleStore& p = sim.state_to_change().particles;
  jiggle(p, sim.spec().l0, 4, 0.0);
  OptionValues options = default_options(FiniteStrainModel::options());
  options.numbers["hourglass"] = 1.0;
  options.choices["hourglass_form"] = consistent ? "consistent" : "frozen";
  FiniteStrainModel model(p, sim.state().bonds, options);
  model.compute_strain(p, sim.state().bonds, p.all());
  model.compute_forces(p, sim.state().bonds, p.moving());
  const auto ref = reference::finite_strain_model(p, sim.state().bonds, 1.0, consistent);
  const double scale = testing::max_abs(ref.fx);
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_NEAR(model.jacobian()[i], ref.jacobian[i], 1e-12) << i;
    if (i < p.moving().begin) continue;
    ASSERT_NEAR(p.fx[i], ref.fx[i], 1e-10 * scale) << i;
    ASSERT_NEAR(p.fy[i], ref.fy[i], 1e-10 * scale) << i;
  }
}
INSTANTIATE_TEST_SUITE_P(Hourglass, FiniteStrainForms, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& param_info) {
                           return param_info.param ? "consistent" : "frozen";
                         });

class EveryModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryModel, RigidRotationIsForceFreeEverywhere) {
  // A small-strain model is not objective: its own test bounds the error.
  if (!model_info(GetParam()).rotation_invariant) GTEST_SKIP() << "not rotation invariant";
  for (double angle : {1.0, -2.2}) {
    Simulation sim(testing::free_block_case(8, 6, false, 1e-7, GetParam()));
    ParticleStore& p = sim.state_to_change().particles;
    const double c = std::cos(angle), s = std::sin(angle);
    for (std::size_t i = 0; i < p.size(); ++i) {
      p.x[i] = 0.5 + c * p.x0[i] - s * p.y0[i];
      p.y[i] = 0.2 + s * p.x0[i] + c * p.y0[i];
      p.theta[i] = angle;
    }
    sim.advance(1);               // one step from rest: any force would show as a velocity
    const double v_scale = 1e-9;  // m/s after 0.1 us: a strain-equivalent below 1e-10
    for (std::size_t i = 0; i < p.size(); ++i) {
      EXPECT_LT(std::abs(p.vx[i]), v_scale) << GetParam() << " particle " << i;
      EXPECT_LT(std::abs(p.vy[i]), v_scale);
    }
    // Round-off only: far below the energy of a 1e-6 strain in every particle.
    const double tiny =
        p.mu[0] * 1e-12 * sim.state().bonds.geometry.volume * static_cast<double>(p.size());
    EXPECT_LT(std::abs(sim.diagnostics().strain_energy), tiny);
  }
}

TEST_P(EveryModel, FreeBlockConservesMomentaWithARigidPlate) {
  Simulation sim(testing::free_block_case(10, 8, true, 2e-7, GetParam()));
  ParticleStore& p = sim.state_to_change().particles;
  std::mt19937_64 rng(21);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t i = p.elastic.begin; i < p.elastic.end; ++i) {
    p.vx[i] = 0.5 * n(rng);
    p.vy[i] = 0.5 * n(rng);
    if (model_info(GetParam()).uses_rotation) p.omega[i] = 200.0 * n(rng);
  }
  const Diagnostics before = sim.diagnostics();
  // Relative to the momentum magnitude sum m |v|: the net momentum of random
  // velocities is a small difference of large terms.
  double p_scale = 0.0;
  for (std::size_t i = p.elastic.begin; i < p.elastic.end; ++i)
    p_scale += std::hypot(p.vx[i], p.vy[i]) / p.inv_mass[i];
  sim.advance(10000);
  const Diagnostics after = sim.diagnostics();
  EXPECT_LT(std::abs(after.momentum_x - before.momentum_x) / p_scale, 1e-12);
  EXPECT_LT(std::abs(after.momentum_y - before.momentum_y) / p_scale, 1e-12);
  // A model that is not rotation invariant (linear_elastic) has an energy
  // that changes under rotation, so its angular momentum is not conserved.
  if (model_info(GetParam()).rotation_invariant) {
    EXPECT_LT(std::abs(after.angular_momentum - before.angular_momentum) /
                  std::abs(before.angular_momentum),
              1e-10);
  }
}

TEST_P(EveryModel, DeterministicAcrossThreadCounts) {
  std::vector<ParticleStore> results;
  for (int threads : {1, 2}) {
    set_thread_count(threads);
    Simulation sim(testing::rod_case({"model=" + GetParam(), "l0=0.001"}));
    sim.advance(300);
    results.push_back(sim.particles());
  }
  set_thread_count(1);
  EXPECT_TRUE(testing::same_bits(results[0], results[1]));
}

INSTANTIATE_TEST_SUITE_P(Models, EveryModel, ::testing::ValuesIn(model_names()));

// A free block thrown into large deformation and rotation: the consistent
// models keep KE + PE to O(dt); the paper model does not.
double energy_drift(const std::string& model, double dt, int steps) {
  Simulation sim(testing::free_block_case(10, 8, false, dt, model));
  ParticleStore& p = sim.state_to_change().particles;
  std::mt19937_64 rng(8);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t i = p.elastic.begin; i < p.elastic.end; ++i) {
    p.vx[i] = 2.0 * n(rng) - 0.1 * (p.y0[i] - 0.004) * 1e3;
    p.vy[i] = 2.0 * n(rng) + 0.1 * (p.x0[i] - 0.005) * 1e3;
    if (model_info(model).uses_rotation) p.omega[i] = 100.0;
  }
  const Diagnostics start = sim.diagnostics();
  const double e0 = start.kinetic_energy + start.strain_energy;
  double worst = 0;
  for (int k = 0; k < 20; ++k) {
    sim.advance(steps / 20);
    const Diagnostics d = sim.diagnostics();
    worst = std::max(worst, std::abs(d.kinetic_energy + d.strain_energy - e0) / e0);
  }
  return worst;
}

TEST(Energy, ConsistentModelsConserveEnergyToFirstOrderInDt) {
  for (const std::string model : {"paper_conservative", "finite_strain"}) {
    const double coarse = energy_drift(model, 2e-7, 20000);
    const double fine = energy_drift(model, 1e-7, 40000);
    EXPECT_LT(fine, 2e-3) << model;
    EXPECT_LT(fine, 0.7 * coarse) << model << ": the drift must shrink with dt";
  }
  // The paper model's pressure force pumps energy in, whatever the dt.
  EXPECT_GT(energy_drift("paper", 1e-7, 40000), 5e-3);
}

}  // namespace
}  // namespace mpsolid
