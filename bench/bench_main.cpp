// Google Benchmark driver of mpsolid's benchmarks. Thread counts come from
// MPSOLID_BENCH_THREADS (default "1 2"; bench/run_scaling.sh sets it), the
// rest from Google Benchmark's flags (--benchmark_filter=...,
// --benchmark_repetitions=5, --benchmark_out=FILE.json).
#include <benchmark/benchmark.h>

#include "bench/registry.hpp"

int main(int argc, char** argv) {
  using namespace mpsolid::bench;
  register_step_benchmarks();
  register_kernel_benchmarks();
  register_skip_work_benchmarks();
  register_neighbor_benchmarks();
  register_contact_benchmarks();
  register_team_benchmarks();
  register_gas_benchmarks();
  register_space_benchmarks();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
