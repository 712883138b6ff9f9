// The step does no work a scene does not ask for; each pair below differs in
// one thing only (paper model, l0 = 2 and 0.5 mm, each thread count):
// - rigid_body: the rod with its rigid plate against the plate made elastic
//   (same particles and bonds): no projection without rigid bodies.
// - walls: the wall as walls against the wall made elastic: walls are
//   outside the force pass and the integration.
// - rotation: the integration with and without the rotation work (spin,
//   angle, half angles), as finite_strain skips it.
// - diagnostics: steps alone, with the run loop's check every 500 steps,
//   and with a check every step: diagnostics run only at checks and frames.
// - neighbours: the neighbour-search time spent inside the step loop (0)
//   and a bond build's cost in steps: no search after set-up.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"
#include "neighbor/bond_search.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/step.hpp"

namespace mpsolid::bench {
namespace {

constexpr long kSkipSpacingsUm[] = {2000, 500};

// Time per step of advance(steps) for a case.
double step_seconds(Simulation& sim, int steps) {
  const auto start = std::chrono::steady_clock::now();
  sim.advance(steps);
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return elapsed.count() / steps;
}

void run_steps(benchmark::State& state, const CaseSpec& spec, int threads) {
  set_thread_count(threads);
  Simulation sim(spec);
  const int steps = repeats_for(sim.particles().size());
  for (auto _ : state) state.SetIterationTime(step_seconds(sim, steps));
  state.counters["rigid_bodies"] = static_cast<double>(sim.state().rigid_bodies.size());
  state.counters["moving"] = static_cast<double>(sim.particles().moving().size());
}

void run_integrate(benchmark::State& state, long l0_um, bool rotation, int threads) {
  set_thread_count(threads);
  Simulation sim(rod(l0_um, "paper"));
  SolverState& s = sim.state_to_change();
  ParticleStore& p = s.particles;
  for (auto* v : {&p.fx, &p.fy, &p.torque}) std::fill(v->begin(), v->end(), 0.0);
  BodyKicks kicks(s.rigid_bodies.size());
  auto integrate = [&]<bool Rotation>() {
    parallel_blocks(p.moving().begin, p.moving().end, [&](std::size_t b, std::size_t e) {
      integrate_block<Rotation>(s, sim.spec().dt, s.step, {b, e}, kicks);
    });
  };
  time_in_team(state, repeats_for(p.size()), [&] {
    if (rotation)
      integrate.template operator()<true>();
    else
      integrate.template operator()<false>();
  });
}

// Steps with a stability check (a strain pass and the energy sums) every
// `check_every` steps (0: none).
void run_checks(benchmark::State& state, long l0_um, int check_every, int threads) {
  set_thread_count(threads);
  Simulation sim(rod(l0_um, "paper"));
  const int steps = check_every > 0 ? check_every : 500;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    sim.advance(steps);
    if (check_every > 0) benchmark::DoNotOptimize(sim.check_stability().ok);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count() / steps);
  }
}

void run_neighbours(benchmark::State& state, long l0_um, int threads) {
  set_thread_count(threads);
  Simulation sim(rod(l0_um, "paper"));
  const double before = sim.timers().seconds(Phase::neighbors);
  const int steps = repeats_for(sim.particles().size());
  double step_time = 0;
  for (auto _ : state) {
    step_time = step_seconds(sim, steps);
    state.SetIterationTime(step_time);
  }
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(build_bonds(sim.particles(), sim.state().bonds.geometry).entry_count());
  const std::chrono::duration<double> build = std::chrono::steady_clock::now() - start;
  state.counters["neighbor_s_in_loop"] = sim.timers().seconds(Phase::neighbors) - before;
  state.counters["bond_build_in_steps"] = build.count() / step_time;
}

}  // namespace

void register_skip_work_benchmarks() {
  for (long l0 : kSkipSpacingsUm)
    for (int t : bench_threads()) {
      auto name = [&](const char* what) {
        return fmt::format("skip/{}/l0_um:{}/threads:{}", what, l0, t);
      };
      // The same rod, each pair differing in one body's kind.
      const std::pair<const char*, std::vector<std::string>> scenes[] = {
          {"rigid_body:with", {}},
          {"rigid_body:without", {"bodies.plate.kind=elastic"}},
          {"walls:walls", {}},
          {"walls:elastic", {"bodies.wall.kind=elastic"}}};
      for (const auto& [scene, overrides] : scenes)
        benchmark::RegisterBenchmark(
            name(scene).c_str(),
            [=, o = overrides](benchmark::State& st) { run_steps(st, rod(l0, "paper", o), t); })
            ->UseManualTime()
            ->MinTime(kPerCallMinTime);
      for (bool rotation : {true, false})
        benchmark::RegisterBenchmark(
            name(rotation ? "rotation:on" : "rotation:off").c_str(),
            [=](benchmark::State& st) { run_integrate(st, l0, rotation, t); })
            ->UseManualTime()
            ->MinTime(kPerCallMinTime);
      for (int every : {0, 500, 1})
        benchmark::RegisterBenchmark(name(every == 0   ? "diagnostics:none"
                                          : every == 1 ? "diagnostics:every_step"
                                                       : "diagnostics:every_500")
                                         .c_str(),
                                     [=](benchmark::State& st) { run_checks(st, l0, every, t); })
            ->UseManualTime()
            ->MinTime(kPerCallMinTime);
      benchmark::RegisterBenchmark(name("neighbours").c_str(),
                                   [=](benchmark::State& st) { run_neighbours(st, l0, t); })
          ->UseManualTime()
          ->MinTime(kPerCallMinTime);
    }
}

}  // namespace mpsolid::bench
