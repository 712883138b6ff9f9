#pragma once
// What every benchmark shares: the rod case at a spacing, the thread counts
// (from MPSOLID_BENCH_THREADS), timing of repeated calls inside one parallel
// region, and the rate counters (particles/s, bonds/s, GFLOP/s, share of peak).
#include <benchmark/benchmark.h>

#include <chrono>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid::bench {

// The spacings of the rod benchmarks, in micrometres: 2, 1, 0.5, 0.25 mm.
inline const std::vector<long> kSpacingsUm = {2000, 1000, 500, 250};

// cases/shock_rod.toml at l0 (micrometres) with the model and extra overrides.
CaseSpec rod(long l0_um, const std::string& model, std::vector<std::string> overrides = {});

// Thread counts from MPSOLID_BENCH_THREADS ("1 2 4 8 16"), default 1 and 2.
std::vector<int> bench_threads();

// Calls per timed iteration for a case of `particles`: enough to hide the
// parallel region's start, at most kMaxRepeats.
inline constexpr int kMaxRepeats = 100;
int repeats_for(std::size_t particles);

// The minimum manual time of a benchmark whose manual time is per call (per
// step, per kernel call) while one iteration makes up to kMaxRepeats calls.
// Google Benchmark runs until the manual time reaches its minimum (0.5 s by
// default), which would be up to 50 s of real time per repetition; this
// keeps it near 0.5 s. Set with ->UseManualTime()->MinTime(kPerCallMinTime).
inline constexpr double kPerCallMinTime = 0.5 / kMaxRepeats;

// Times `repeats` calls of body() inside one parallel region (as the step
// loop runs them) and reports the time per call (UseManualTime).
template <class Body>
void time_in_team(benchmark::State& state, int repeats, Body&& body) {
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    run_in_team([&] {
      for (int k = 0; k < repeats; ++k) body();
    });
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count() / repeats);
  }
}

// Assumed peak of one core (AMD EPYC Zen 4 at 2.6 GHz, as lscpu reports it):
// 2 x 256-bit FMA pipes = 16 double-precision flops per cycle, 41.6 GFLOP/s.
// This build (x86-64 baseline SSE2, -ffp-contract=off: no FMA) can issue at
// most 2 x 128-bit multiplies and 2 x 128-bit adds, 8 flops per cycle; the
// kernels are mostly scalar gathers, 4 flops per cycle.
inline constexpr double kPeakFlopsPerCore = 16 * 2.6e9;

// Rates per call: particles/s, bond entries/s (each bond is seen from both
// ends) and flops/s from hand counts, with the share of the cores' peak.
void rate_counters(benchmark::State& state, double particles, double bond_entries,
                   double flops_per_call, int threads);

}  // namespace mpsolid::bench
