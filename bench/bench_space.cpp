// The per-particle gather kernels in space (kernels/gradient_gather_model.hpp,
// kernels/paper_gather_model.hpp): a step of a free 3D rubber cube of n^3
// particles (finite_strain, paper), and in the plane the rod's step with the
// gather kernel beside the slot kernel it could replace. Rates in
// particle-steps per second.
#include <fmt/format.h>

#include <cmath>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"
#include "kernels/finite_strain_model.hpp"
#include "kernels/gradient_gather_model.hpp"
#include "kernels/paper_gather_model.hpp"
#include "neighbor/bond_search.hpp"
#include "src/core/region3.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/step.hpp"

namespace mpsolid::bench {
namespace {

// An n^3 rubber cube at l0 = 1 mm, stretched 1 % along x so that it moves.
SolverState rubber_cube(int n) {
  const double l0 = 1e-3, side = n * l0;
  SolverState s;
  ParticleStore& p = s.particles;
  p.dimension = 3;
  const std::vector<Point3> sites =
      fill_shape3({BoxRegion{{0, side}, {0, side}, {0, side}}, {}}, l0);
  p.resize(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    p.x0[i] = sites[i].x;
    p.y0[i] = sites[i].y;
    p.z0[i] = sites[i].z;
    p.x[i] = 1.01 * sites[i].x;
    p.y[i] = sites[i].y;
    p.z[i] = sites[i].z;
    p.id[i] = static_cast<std::int32_t>(i);
    p.lambda[i] = 2.8e7;
    p.mu[i] = 9.4e5;
    p.inv_mass[i] = 1.0 / (1100.0 * l0 * l0 * l0);
  }
  p.set_kind_ranges();
  s.bonds = build_bonds(p, bond_geometry_3d(l0));
  return s;
}

// Steps per timed iteration: enough to hide the team's start.
int steps_for(std::size_t particles) {
  return static_cast<int>(
      std::clamp<std::size_t>(2'000'000 / std::max<std::size_t>(particles, 1), 2, kMaxRepeats));
}

template <class Model>
void time_steps(benchmark::State& state, Model& model, SolverState& s, double dt, int threads) {
  PhaseTimers timers;
  const int steps = steps_for(s.particles.size());
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    advance_steps(model, s, dt, timers, steps);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count() / steps);
  }
  rate_counters(state, static_cast<double>(s.particles.size()),
                static_cast<double>(s.bonds.entry_count()), 0.0, threads);
}

void space_step(benchmark::State& state, int n, int threads) {
  set_thread_count(threads);
  SolverState s = rubber_cube(n);
  GradientGatherModel<3, NeoHookeanLaw> model(s.particles, s.bonds,
                                              default_options(hourglass_option_table()));
  const double dt = 0.2e-3 / std::sqrt((2.8e7 + 2 * 9.4e5) / 1100.0);
  time_steps(state, model, s, dt, threads);
}

// The same cube with the paper model (a quaternion per particle).
void space_paper_step(benchmark::State& state, int n, int threads) {
  set_thread_count(threads);
  SolverState s = rubber_cube(n);
  PaperGatherModel<false> model(s.particles, s.bonds, {});
  const double dt = 0.2e-3 / std::sqrt((2.8e7 + 2 * 9.4e5) / 1100.0);
  time_steps(state, model, s, dt, threads);
}

// The rod's finite_strain step with the slot kernel (gather = false) or the
// gather kernel, from the same state.
void plane_step(benchmark::State& state, long l0_um, bool gather, int threads) {
  set_thread_count(threads);
  Simulation sim(rod(l0_um, "finite_strain"));
  SolverState& s = sim.state_to_change();
  const OptionValues& options = sim.spec().model_options;
  if (gather) {
    GradientGatherModel<2, NeoHookeanLaw> model(s.particles, s.bonds, options);
    time_steps(state, model, s, sim.spec().dt, threads);
  } else {
    FiniteStrainModel model(s.particles, s.bonds, options);
    time_steps(state, model, s, sim.spec().dt, threads);
  }
}

}  // namespace

void register_space_benchmarks() {
  for (const int threads : bench_threads()) {
    for (const int n : {16, 32, 64})
      benchmark::RegisterBenchmark(fmt::format("space/step/n:{}/threads:{}", n, threads).c_str(),
                                   [=](benchmark::State& st) { space_step(st, n, threads); })
          ->UseManualTime()
          ->MinTime(kPerCallMinTime);
    for (const int n : {16, 32, 64})
      benchmark::RegisterBenchmark(
          fmt::format("space/step/paper/n:{}/threads:{}", n, threads).c_str(),
          [=](benchmark::State& st) { space_paper_step(st, n, threads); })
          ->UseManualTime()
          ->MinTime(kPerCallMinTime);
    for (const long l0 : {1000L, 500L})
      for (const bool gather : {false, true})
        benchmark::RegisterBenchmark(
            fmt::format("plane/step/{}/l0_um:{}/threads:{}", gather ? "gather" : "slots", l0,
                        threads)
                .c_str(),
            [=](benchmark::State& st) { plane_step(st, l0, gather, threads); })
            ->UseManualTime()
            ->MinTime(kPerCallMinTime);
  }
}

}  // namespace mpsolid::bench
