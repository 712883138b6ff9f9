// The fast gather kernels against the plain pair-loop reference (paper's
// Eq. 3-7 in acceleration form) on a randomly deformed, rotated rod.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/paper_model.hpp"
#include "kernels/reference/reference_kernels.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(PaperModel, KernelsMatchThePlainReference) {
  Simulation sim(testing::rod_case());
  ParticleStore& p = sim.particles();
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  const double l0 = sim.spec().l0;
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    p.x[i] += 0.05 * l0 * n(rng);
    p.y[i] += 0.05 * l0 * n(rng);
    p.theta[i] = 0.4 + 0.05 * n(rng);  // a large common rotation plus noise
  }
  sim.refresh_fields();
  PaperModel(p, sim.state().bonds, {}).compute_forces(p, sim.state().bonds, p.moving());
  const reference::PaperResult ref = reference::paper_model(p, sim.state().bonds);

  auto compare = [&](const std::vector<double>& fast, const std::vector<double>& slow,
                     std::size_t begin, const char* what) {
    const double scale = testing::max_abs(slow);
    ASSERT_GT(scale, 0.0) << what;
    for (std::size_t i = begin; i < p.size(); ++i)
      ASSERT_NEAR(fast[i], slow[i], 1e-11 * scale) << what << " of particle " << i;
  };
  compare(p.strain, ref.strain, 0, "strain");
  compare(p.pressure, ref.pressure, 0, "pressure");
  compare(p.fx, ref.fx, p.moving().begin, "fx");
  compare(p.fy, ref.fy, p.moving().begin, "fy");
  compare(p.torque, ref.torque, p.moving().begin, "torque");
}

}  // namespace
}  // namespace mpsolid
