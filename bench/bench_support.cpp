#include "bench/bench_support.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "src/solver/case_loader.hpp"

namespace mpsolid::bench {

CaseSpec rod(long l0_um, const std::string& model, std::vector<std::string> overrides) {
  overrides.push_back("l0=" + std::to_string(static_cast<double>(l0_um) * 1e-6));
  overrides.push_back("model=" + model);
  return load_case(std::string(MPSOLID_SOURCE_DIR) + "/cases/shock_rod.toml", overrides);
}

std::vector<int> bench_threads() {
  std::vector<int> threads;
  if (const char* env = std::getenv("MPSOLID_BENCH_THREADS")) {
    std::istringstream in(env);
    for (int t = 0; in >> t;)
      if (t > 0) threads.push_back(t);
  }
  if (threads.empty()) threads = {1, 2};
  return threads;
}

int repeats_for(std::size_t particles) {
  return static_cast<int>(
      std::clamp<std::size_t>(2'000'000 / std::max<std::size_t>(particles, 1), 2, kMaxRepeats));
}

void rate_counters(benchmark::State& state, double particles, double bond_entries,
                   double flops_per_call, int threads) {
  using benchmark::Counter;
  state.counters["particles"] = particles;
  state.counters["particles/s"] = Counter(particles, Counter::kIsIterationInvariantRate);
  state.counters["bonds/s"] = Counter(bond_entries, Counter::kIsIterationInvariantRate);
  state.counters["GFLOP/s"] = Counter(flops_per_call * 1e-9, Counter::kIsIterationInvariantRate);
  state.counters["peak_share"] =
      Counter(flops_per_call / (kPeakFlopsPerCore * threads), Counter::kIsIterationInvariantRate);
}

}  // namespace mpsolid::bench
