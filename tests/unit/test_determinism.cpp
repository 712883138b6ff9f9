// Same bits at any thread count: every kernel is a gather in a fixed bond
// order and every global sum goes through the ordered helper.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "kernels/model_registry.hpp"
#include "src/core/parallel.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/gas_coupling.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

struct Snapshot {
  ParticleStore particles;
  Diagnostics diagnostics;
};

Snapshot run_case(int threads, const CaseSpec& spec, std::int64_t steps = 1000) {
  set_thread_count(threads);
  Simulation sim(spec);
  sim.advance(steps);
  Snapshot s{sim.particles(), sim.diagnostics()};
  s.particles = sim.particles();
  return s;
}

void expect_same_bits(const CaseSpec& spec, std::int64_t steps = 1000) {
  const Snapshot one = run_case(1, spec, steps);
  for (int threads : {2, 3, 4}) {
    const Snapshot many = run_case(threads, spec, steps);
    EXPECT_TRUE(testing::same_bits(one.particles, many.particles)) << threads << " threads";
    EXPECT_EQ(one.diagnostics.kinetic_energy, many.diagnostics.kinetic_energy);
    EXPECT_EQ(one.diagnostics.strain_energy, many.diagnostics.strain_energy);
    EXPECT_EQ(one.diagnostics.angular_momentum, many.diagnostics.angular_momentum);
    EXPECT_EQ(one.diagnostics.external_work, many.diagnostics.external_work);
  }
  set_thread_count(available_cores());
}

TEST(Determinism, RodCaseIsBitIdenticalAt1To4Threads) {
  expect_same_bits(testing::rod_case());
}

// Pressures: on the rod's rigid plate (ramped), and a blast wave on half of
// a free disk, whose surface nodes spread its forces over its particles.
TEST(Determinism, PressureCasesAreBitIdenticalAt1To4Threads) {
  expect_same_bits(
      load_case(testing::source_path("cases/shock_rod_pressure.toml"),
                {"l0=0.001", "loads.shock.history=\"ramp\"", "loads.shock.rise_time=3e-6"}));
  expect_same_bits(load_case(testing::source_path("cases/disk_blast.toml")), 150);
}

// The gas pushing a panel cut across the threads (the Giordano panel,
// coarse, the shock started 2 mm from it): the particles, the energies and
// the gas's fields are the same bits at 1-4 threads. In batches with a read
// between, as the run loop checks: a gas window then starts with the
// threads' parts ahead of the whole state, or level with it.
TEST(Determinism, GasOnAPanelIsBitIdenticalAt1To4Threads) {
  const CaseSpec spec = load_case(testing::source_path("cases/giordano_panel.toml"),
                                  {"gas.cell=0.001", "gas.shock.x=-0.002"});
  std::vector<double> first_pressure;
  Snapshot first;
  for (int threads : {1, 2, 3, 4}) {
    set_thread_count(threads);
    Simulation sim(spec);
    for (int batch = 0; batch < 10; ++batch) {
      // Every other batch ends where the next window starts.
      const std::int64_t to_window = sim.gas()->next_exchange() - sim.step();
      sim.advance(batch % 2 == 0 && to_window > 0 ? to_window : 91 + 23 * (batch % 3));
      sim.diagnostics();
    }
    const Snapshot s{sim.particles(), sim.diagnostics()};
    const GasFrame gas = sim.gas_frame();
    if (threads == 1) {
      first = s;
      first_pressure = gas.pressure;
      EXPECT_GT(s.diagnostics.kinetic_energy, 0.0);  // struck
      continue;
    }
    EXPECT_TRUE(testing::same_bits(first.particles, s.particles)) << threads << " threads";
    EXPECT_EQ(first.diagnostics.external_work, s.diagnostics.external_work);
    EXPECT_EQ(first.diagnostics.gas.energy, s.diagnostics.gas.energy);
    EXPECT_EQ(first_pressure.size(), gas.pressure.size());
    EXPECT_TRUE(std::memcmp(first_pressure.data(), gas.pressure.data(),
                            sizeof(double) * gas.pressure.size()) == 0)
        << threads << " threads";
  }
  set_thread_count(available_cores());
}

// At l0 = 1 mm every kernel range is large enough to be split across threads.
TEST(Determinism, FinerRodIsBitIdenticalAt1To4ThreadsForEveryModel) {
  for (const std::string& model : model_names()) {
    SCOPED_TRACE(model);
    expect_same_bits(testing::rod_case({"l0=0.001", "model=" + model}));
  }
}

// A batch of steps runs in one parallel region, with the half angles carried
// by the integration and a rigid body projected by the thread that owns its
// particles; steps one by one recompute the half angles each time. Both, in
// any batch sizes, give the same bits at 1, 2 and 3 threads, for every model,
// with a rigid body inside one thread's block (the rod, with its load switching
// on mid-batch) and one that spans the blocks (a small block, a large plate).
// Sets every particle moving and spinning (deterministic, varied values), so
// rigid bodies turn and every rotation-dependent path is exercised.
void stir(Simulation& sim) {
  ParticleStore& p = sim.state_to_change().particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto k = static_cast<double>(i);
    p.vx[i] = 0.5 * std::sin(1.3 * k);
    p.vy[i] = 0.5 * std::cos(0.7 * k);
    p.omega[i] = 200.0 * std::sin(0.9 * k);
  }
}

void expect_batches_same_bits(const CaseSpec& spec) {
  constexpr std::int64_t kSteps = 30;
  set_thread_count(1);
  Simulation reference(spec);
  stir(reference);
  for (std::int64_t k = 0; k < kSteps; ++k) reference.advance(1);
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    for (std::int64_t first_batch : {kSteps, std::int64_t{7}}) {
      Simulation sim(spec);
      stir(sim);
      sim.advance(first_batch);
      sim.advance(kSteps - first_batch);
      const auto& a = reference.state();
      const auto& b = sim.state();
      EXPECT_EQ(b.step, kSteps);
      EXPECT_TRUE(testing::same_bits(a.particles, b.particles))
          << threads << " threads, first batch " << first_batch;
      ASSERT_EQ(a.rigid_bodies.size(), b.rigid_bodies.size());
      for (std::size_t k = 0; k < a.rigid_bodies.size(); ++k) {
        EXPECT_EQ(a.rigid_bodies[k].xg, b.rigid_bodies[k].xg);
        EXPECT_EQ(a.rigid_bodies[k].angle, b.rigid_bodies[k].angle);
        EXPECT_EQ(a.rigid_bodies[k].omega, b.rigid_bodies[k].omega);
      }
      for (std::size_t k = 0; k < a.loads.size(); ++k) {
        EXPECT_EQ(a.loads[k].active, b.loads[k].active);
        EXPECT_EQ(a.loads[k].cx_on, b.loads[k].cx_on);
        EXPECT_EQ(a.loads[k].factor, b.loads[k].factor);
        EXPECT_EQ(a.loads[k].work, b.loads[k].work);
        EXPECT_EQ(a.loads[k].cx_last, b.loads[k].cx_last);
      }
    }
  }
  set_thread_count(available_cores());
}

TEST(Determinism, BatchedStepsEqualSingleStepsAt1And2And3Threads) {
  for (const std::string& model : model_names()) {
    SCOPED_TRACE(model);
    // The load switches on at step 12, inside the first batch.
    expect_batches_same_bits(
        testing::rod_case({"model=" + model, "l0=0.004", "loads.shock.start=1.2e-7"}));
    // A ramp: the factor and the work change every step.
    expect_batches_same_bits(
        testing::rod_case({"model=" + model, "l0=0.004", "loads.shock.history=\"ramp\"",
                           "loads.shock.rise_time=3e-7"}));
    expect_batches_same_bits(testing::free_block_case(4, 4, true, 1e-7, model));
    // A pressure: its forces are computed at the step's start, by one thread.
    expect_batches_same_bits(
        load_case(testing::source_path("cases/disk_blast.toml"), {"model=" + model, "l0=0.002"}));
    // Holds are cleared block by block: the same bits too.
    expect_batches_same_bits(testing::rod_case(
        {"model=" + model, "l0=0.004", "bodies.rod.hold=\"y\"", "bodies.rod.spin=50.0"}));
  }
}

TEST(Holds, HeldComponentStaysZeroAtAnyThreadCount) {
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    Simulation sim(
        testing::rod_case({"l0=0.004", "bodies.rod.hold=\"y\"", "bodies.rod.spin=50.0"}));
    sim.advance(200);
    const ParticleStore& p = sim.particles();
    const Range rod = sim.state().body_ranges[1];  // bodies in name order: plate, rod, wall
    double vx = 0;
    for (std::size_t i = rod.begin; i < rod.end; ++i) {
      ASSERT_EQ(p.vy[i], 0.0) << threads << " threads, particle " << p.id[i];
      ASSERT_EQ(p.y[i], p.y0[i]);
      vx = std::max(vx, std::abs(p.vx[i]));
    }
    EXPECT_GT(vx, 0.5);  // the spin's x part (up to 0.9 m/s) still moves it
  }
  set_thread_count(available_cores());
}

}  // namespace
}  // namespace mpsolid
