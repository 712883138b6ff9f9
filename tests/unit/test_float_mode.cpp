// numerics.flush_subnormals: subnormals are flushed to zero inside the
// solver's parallel regions, on every thread, and nowhere else; flushing
// changes no position or energy bit of a rod run whose far field is full of
// subnormals, and the rest differs only far below any physical scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include "src/core/float_mode.hpp"
#include "src/core/parallel.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

#if defined(__SSE2__) || defined(__aarch64__)
constexpr bool kCanFlush = true;
#else
constexpr bool kCanFlush = false;
#endif

// The smallest normal double times 0.5: a subnormal result (volatile, so the
// compiler cannot fold it at compile time under the caller's mode).
double subnormal_product() {
  volatile double tiny = 2.2250738585072014e-308;
  volatile double half = 0.5;
  return tiny * half;
}

// What each of `threads` threads computes inside one parallel region.
std::vector<double> products_in_team(int threads) {
  set_thread_count(threads);
  std::vector<double> out(1024, -1.0);
  parallel_for(0, out.size(), [&](std::size_t i) { out[i] = subnormal_product(); });
  set_thread_count(available_cores());
  return out;
}

int subnormal_count(const std::vector<double>& v) {
  int n = 0;
  for (double x : v) n += std::fpclassify(x) == FP_SUBNORMAL;
  return n;
}

TEST(FloatMode, SolverRegionsFlushOnEveryThreadAndRestoreTheCaller) {
  if (!kCanFlush) GTEST_SKIP() << "no flush-to-zero control on this architecture";
  ASSERT_EQ(std::fpclassify(subnormal_product()), FP_SUBNORMAL) << "IEEE outside the solver";
  set_flush_subnormals(true);
  for (int threads : {1, 2, 3})
    for (double x : products_in_team(threads)) ASSERT_EQ(x, 0.0) << threads << " threads";
  bool ran = false;
  run_in_team([&] { serial_section([&] { ran = subnormal_product() == 0.0; }); });
  set_flush_subnormals(false);
  EXPECT_TRUE(ran);
  EXPECT_EQ(std::fpclassify(subnormal_product()), FP_SUBNORMAL) << "the caller's mode is restored";
}

TEST(FloatMode, ByDefaultTheSolverKeepsSubnormals) {
  ASSERT_FALSE(flush_subnormals());
  const std::vector<double> products = products_in_team(2);
  EXPECT_EQ(subnormal_count(products), static_cast<int>(products.size()));
}

struct RodRun {
  ParticleStore particles;
  Diagnostics diagnostics;
  int subnormals = 0;  // subnormal velocities, forces and strains seen after some step
};

// The rod at 1 mm: in its first steps the wave has not crossed it, and the
// far field holds subnormal velocities, forces and strains.
RodRun run_rod(bool flush, int threads) {
  set_thread_count(threads);
  Simulation sim(testing::rod_case(
      {"l0=0.001", flush ? "numerics.flush_subnormals=true" : "numerics.flush_subnormals=false"}));
  RodRun r;
  for (int batch = 0; batch < 6; ++batch) {
    sim.advance(100);
    const ParticleStore& p = sim.particles();
    for (const auto* v : {&p.vx, &p.vy, &p.fx, &p.fy, &p.strain, &p.omega})
      r.subnormals = std::max(r.subnormals, subnormal_count(*v));
  }
  r.particles = sim.particles();
  r.diagnostics = sim.diagnostics();
  set_flush_subnormals(false);
  set_thread_count(available_cores());
  return r;
}

bool same(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(FloatMode, FlushingChangesNoPositionOrEnergyAndTheRestOnlyBelow1e270) {
  if (!kCanFlush) GTEST_SKIP() << "no flush-to-zero control on this architecture";
  const RodRun ieee = run_rod(false, 1);
  const RodRun flushed = run_rod(true, 2);
  ASSERT_GT(ieee.subnormals, 0) << "the run must have subnormals for this test to mean anything";
  EXPECT_EQ(flushed.subnormals, 0);
  EXPECT_TRUE(same(ieee.particles.x, flushed.particles.x));
  EXPECT_TRUE(same(ieee.particles.y, flushed.particles.y));
  EXPECT_EQ(ieee.diagnostics.kinetic_energy, flushed.diagnostics.kinetic_energy);
  EXPECT_EQ(ieee.diagnostics.strain_energy, flushed.diagnostics.strain_energy);
  EXPECT_EQ(ieee.diagnostics.external_work, flushed.diagnostics.external_work);
  EXPECT_EQ(ieee.diagnostics.angular_momentum, flushed.diagnostics.angular_momentum);
  // Angles, velocities, forces and strains differ only in the far field, where
  // a flushed subnormal has grown (times a stiffness) into a tiny normal value.
  const ParticleStore& a = ieee.particles;
  const ParticleStore& b = flushed.particles;
  int differing = 0;
  double largest = 0;
  for (const auto& [u, v] : {std::pair{&a.theta, &b.theta},
                             {&a.vx, &b.vx},
                             {&a.vy, &b.vy},
                             {&a.fx, &b.fx},
                             {&a.fy, &b.fy},
                             {&a.strain, &b.strain},
                             {&a.omega, &b.omega},
                             {&a.torque, &b.torque}})
    for (std::size_t i = 0; i < u->size(); ++i)
      if ((*u)[i] != (*v)[i]) {
        ++differing;
        largest = std::max({largest, std::abs((*u)[i]), std::abs((*v)[i])});
      }
  EXPECT_GT(differing, 0);
  EXPECT_LT(largest, 1e-270);  // measured: 4e-281
  std::printf(
      "subnormal entries (IEEE run, most in one array): %d; differing entries: %d, "
      "all below %.3g in magnitude\n",
      ieee.subnormals, differing, largest);
}

}  // namespace
}  // namespace mpsolid
