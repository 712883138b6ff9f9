// The team's own cost per loop, no physics, on the 2 mm rod's particle
// count (1,130) and the 0.5 mm rod's (18,080): what a step's loops cost
// before any bond term is computed (docs/performance.md, two threads).
//  - team/empty_loop: a loop that claims its chunks and meets the others at
//    the closing barrier, and nothing else;
//  - team/write_then_read_band/band:B: two loops, as a pass and the next
//    one: each thread writes its block of an array, then each particle reads
//    the values B indices either side of it (B = 100: the two lattice rows a
//    2 mm rod's bonds reach), so about B / 8 cache lines written by one
//    thread cross to the other at each block boundary. Time per pair of
//    loops.
#include <fmt/format.h>

#include <vector>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"

namespace mpsolid::bench {
namespace {

// Loops per timed region (its start is hidden), and the manual time per loop
// that makes about half a second of real time.
constexpr int kLoops = 1000;

void run_empty_loop(benchmark::State& state, std::size_t n, int threads) {
  set_thread_count(threads);
  time_in_team(state, kLoops, [&] { parallel_blocks(0, n, [](std::size_t, std::size_t) {}); });
  state.counters["threads"] = threads;
}

void run_band(benchmark::State& state, std::size_t n, std::size_t band, int threads) {
  set_thread_count(threads);
  std::vector<double> written(n, 1.0), read(n, 0.0);
  time_in_team(state, kLoops, [&] {
    parallel_blocks(0, n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) written[i] += 1.0;
    });
    parallel_blocks(0, n, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i)
        read[i] = written[i >= band ? i - band : i] + written[i + band < n ? i + band : i];
    });
  });
  benchmark::DoNotOptimize(read.data());
  state.counters["threads"] = threads;
}

}  // namespace

void register_team_benchmarks() {
  for (const std::size_t n : {std::size_t{1130}, std::size_t{18080}})
    for (int threads : bench_threads()) {
      benchmark::RegisterBenchmark(
          fmt::format("team/empty_loop/particles:{}/threads:{}", n, threads).c_str(),
          [=](benchmark::State& st) { run_empty_loop(st, n, threads); })
          ->UseManualTime()
          ->MinTime(0.5 / kLoops);
      for (const std::size_t band : {std::size_t{0}, std::size_t{100}})
        benchmark::RegisterBenchmark(
            fmt::format("team/write_then_read_band/band:{}/particles:{}/threads:{}", band, n,
                        threads)
                .c_str(),
            [=](benchmark::State& st) { run_band(st, n, band, threads); })
            ->UseManualTime()
            ->MinTime(0.5 / kLoops);
    }
}

}  // namespace mpsolid::bench
