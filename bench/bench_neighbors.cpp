// The bond build (neighbour search and bond constants, done once at set-up):
// cell list against k-d tree, by size.
#include <fmt/format.h>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"
#include "neighbor/bond_search.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid::bench {
namespace {

void run_bond_build(benchmark::State& state, long l0_um, NeighborMethod method) {
  set_thread_count(1);
  Simulation sim(rod(l0_um, "paper"));
  for (auto _ : state)
    benchmark::DoNotOptimize(
        build_bonds(sim.particles(), sim.state().bonds.geometry, method).entry_count());
  state.counters["particles"] = static_cast<double>(sim.particles().size());
}

}  // namespace

void register_neighbor_benchmarks() {
  const std::pair<NeighborMethod, const char*> methods[] = {
      {NeighborMethod::cell_list, "cell_list"}, {NeighborMethod::kdtree, "kdtree"}};
  for (long l0 : kSpacingsUm)
    for (const auto& [method, name] : methods)
      benchmark::RegisterBenchmark(
          fmt::format("bond_build/{}/l0_um:{}", name, l0).c_str(),
          [=, m = method](benchmark::State& st) { run_bond_build(st, l0, m); })
          ->Unit(benchmark::kMillisecond);
}

}  // namespace mpsolid::bench
