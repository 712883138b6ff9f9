// Google Benchmark: the step's kernels and the whole step on the paper's rod
// case at several resolutions and thread counts, and the bond build (cell
// list against k-d tree). Run: build/release/bench/bench_solver
// (--benchmark_filter=..., --benchmark_repetitions=5 for medians).
#include <benchmark/benchmark.h>

#include <string>

#include "kernels/half_angles.hpp"
#include "kernels/paper_model.hpp"
#include "src/case_reader.hpp"
#include "src/parallel.hpp"
#include "src/simulation.hpp"

namespace mpsolid {
namespace {

// l0 in micrometres from the benchmark argument.
CaseSpec rod(long l0_um) {
  return read_case(std::string(MPSOLID_SOURCE_DIR) + "/cases/shock_rod.toml",
                   {"l0=" + std::to_string(static_cast<double>(l0_um) * 1e-6)});
}

void counters(benchmark::State& state, const Simulation& sim) {
  const double particles = static_cast<double>(sim.particles().size());
  const double bonds = static_cast<double>(sim.state().bonds.entry_count());
  state.counters["particles"] = particles;
  state.counters["particle_steps/s"] =
      benchmark::Counter(particles, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bond_entries/s"] =
      benchmark::Counter(bonds, benchmark::Counter::kIsIterationInvariantRate);
}

void BM_Step(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(1)));
  Simulation sim(rod(state.range(0)));
  for (auto _ : state) sim.advance(1);
  counters(state, sim);
}

void BM_HalfAngles(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(1)));
  Simulation sim(rod(state.range(0)));
  sim.advance(10);
  for (auto _ : state) compute_half_angles(sim.particles(), sim.particles().moving());
  counters(state, sim);
}

void BM_StrainPass(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(1)));
  Simulation sim(rod(state.range(0)));
  sim.advance(10);
  for (auto _ : state)
    PaperModel().compute_strain(sim.particles(), sim.state().bonds, sim.particles().all());
  counters(state, sim);
}

void BM_ForcePass(benchmark::State& state) {
  set_thread_count(static_cast<int>(state.range(1)));
  Simulation sim(rod(state.range(0)));
  sim.advance(10);
  for (auto _ : state)
    PaperModel().compute_forces(sim.particles(), sim.state().bonds, sim.particles().moving());
  counters(state, sim);
}

void BM_BondBuild(benchmark::State& state) {
  set_thread_count(1);
  Simulation sim(rod(state.range(0)));
  const auto method = static_cast<NeighborMethod>(state.range(1));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        build_bonds(sim.particles(), sim.state().bonds.constants, method).entry_count());
  state.counters["particles"] = static_cast<double>(sim.particles().size());
}

// l0 = 2, 1, 0.5, 0.25 mm; 1 and 2 threads.
void resolutions_and_threads(benchmark::internal::Benchmark* b) {
  for (long l0 : {2000, 1000, 500, 250})
    for (long threads : {1, 2}) b->Args({l0, threads});
  b->ArgNames({"l0_um", "threads"})->UseRealTime();
}

BENCHMARK(BM_Step)->Apply(resolutions_and_threads);
BENCHMARK(BM_HalfAngles)->Apply(resolutions_and_threads);
BENCHMARK(BM_StrainPass)->Apply(resolutions_and_threads);
BENCHMARK(BM_ForcePass)->Apply(resolutions_and_threads);
BENCHMARK(BM_BondBuild)
    ->ArgsProduct({{2000, 1000, 500, 250},
                   {static_cast<long>(NeighborMethod::cell_list),
                    static_cast<long>(NeighborMethod::kdtree)}})
    ->ArgNames({"l0_um", "method"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mpsolid

BENCHMARK_MAIN();
