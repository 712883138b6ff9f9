// Same bits at any thread count: every kernel is a gather in a fixed bond
// order and every global sum goes through the ordered helper.
#include <gtest/gtest.h>

#include "src/parallel.hpp"
#include "src/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

struct Snapshot {
  ParticleStore particles;
  Diagnostics diagnostics;
};

Snapshot run_rod(int threads, const std::vector<std::string>& overrides) {
  set_thread_count(threads);
  Simulation sim(testing::rod_case(overrides));
  sim.advance(1000);
  Snapshot s{sim.particles(), sim.diagnostics()};
  s.particles = sim.particles();
  return s;
}

void expect_same_bits(const std::vector<std::string>& overrides) {
  const Snapshot one = run_rod(1, overrides);
  for (int threads : {2, 4}) {
    const Snapshot many = run_rod(threads, overrides);
    EXPECT_TRUE(testing::same_bits(one.particles, many.particles)) << threads << " threads";
    EXPECT_EQ(one.diagnostics.kinetic_energy, many.diagnostics.kinetic_energy);
    EXPECT_EQ(one.diagnostics.strain_energy, many.diagnostics.strain_energy);
    EXPECT_EQ(one.diagnostics.angular_momentum, many.diagnostics.angular_momentum);
    EXPECT_EQ(one.diagnostics.external_work, many.diagnostics.external_work);
  }
  set_thread_count(available_cores());
}

TEST(Determinism, RodCaseIsBitIdenticalAt1And2And4Threads) {
  expect_same_bits({});
}

// At l0 = 1 mm every kernel range is large enough to be split across threads.
TEST(Determinism, FinerRodIsBitIdenticalAt1And2And4Threads) {
  expect_same_bits({"l0=0.001"});
}

}  // namespace
}  // namespace mpsolid
