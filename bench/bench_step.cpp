// The whole step (Simulation::advance: batches of steps in one parallel
// region), for every model, on the rod at l0 = 2, 1, 0.5, 0.25 mm and each
// thread count, with IEEE subnormals (the default, flush:0) and with
// numerics.flush_subnormals (flush:1). Each benchmark starts the rod at rest,
// so the far field holds subnormals while the wave crosses it (more of them
// on finer rods and in the far thread's block). Time per step; flops are the
// kernels' hand counts summed.
#include <fmt/format.h>

#include <chrono>

#include "bench/bench_support.hpp"
#include "bench/flop_counts.hpp"
#include "bench/registry.hpp"
#include "kernels/model_registry.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid::bench {
namespace {

void run_step(benchmark::State& state, const std::string& model, long l0_um, bool flush,
              int threads) {
  set_thread_count(threads);
  Simulation sim(
      rod(l0_um, model,
          {flush ? "numerics.flush_subnormals=true" : "numerics.flush_subnormals=false"}));
  const ParticleStore& p = sim.particles();
  const BondTable& bonds = sim.state().bonds;
  const int steps = repeats_for(p.size());
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    sim.advance(steps);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count() / steps);
  }
  const FlopCounts f = flop_counts(model);
  const auto n = static_cast<double>(p.size());
  const auto moving = static_cast<double>(p.moving().size());
  const auto entries = static_cast<double>(bonds.entry_count());
  const auto moving_entries =
      static_cast<double>(bonds.begin(p.moving().end) - bonds.begin(p.moving().begin));
  const double flops = entries * f.strain_entry + n * f.strain_particle +
                       moving_entries * f.force_entry + moving * f.force_particle +
                       moving * f.integrate_particle +
                       static_cast<double>(p.rigid.size()) * kRigidFlopsPerParticle;
  rate_counters(state, n, entries, flops, threads);
}

}  // namespace

void register_step_benchmarks() {
  for (const std::string& model : model_names())
    for (long l0 : kSpacingsUm)
      for (bool flush : {false, true})
        for (int threads : bench_threads())
          benchmark::RegisterBenchmark(
              fmt::format("step/{}/l0_um:{}/flush:{}/threads:{}", model, l0, int{flush}, threads)
                  .c_str(),
              [=](benchmark::State& st) { run_step(st, model, l0, flush, threads); })
              ->UseManualTime()
              ->MinTime(kPerCallMinTime);
}

}  // namespace mpsolid::bench
