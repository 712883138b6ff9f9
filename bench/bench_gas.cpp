// The gas solver's speed: cell updates per second (interior cells times
// steps, each step two flux evaluations) on a 2D box with a blast in it, at
// 100 x 100 and 400 x 400 cells, each thread count.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"
#include "src/core/parallel.hpp"
#include "src/gas/gas_solver.hpp"

namespace mpsolid::bench {
namespace {

GasSolver<2> blast_box(int n) {
  GasGrid<2> g;
  g.cells = {n, n};
  g.h = 1.0 / n;
  GasSolver<2> gas(g, 1.4, {});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool inside = std::hypot(i + 0.5 - 0.3 * n, j + 0.5 - 0.4 * n) < 0.1 * n;
      gas.set({i, j}, GasPrimitive<2>{inside ? 3.0 : 1.2, {0.0, 0.0}, inside ? 5e5 : 1e5});
    }
  return gas;
}

void run_gas(benchmark::State& state, int n, int threads) {
  set_thread_count(threads);
  GasSolver<2> gas = blast_box(n);
  const double dt = 0.5 * gas.stable_dt(0.8);
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    gas.advance(dt);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  state.counters["cell_updates_per_s"] =
      benchmark::Counter(static_cast<double>(n) * n * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
  state.counters["threads"] = threads;
}

}  // namespace

void register_gas_benchmarks() {
  for (const int n : {100, 400})
    for (int threads : bench_threads())
      benchmark::RegisterBenchmark(
          fmt::format("gas/step/cells:{}x{}/threads:{}", n, n, threads).c_str(),
          [=](benchmark::State& st) { run_gas(st, n, threads); })
          ->UseManualTime();
}

}  // namespace mpsolid::bench
