// What contact costs: the step of the 55.9 kN rod in the experiment's
// geometry (cases/shock_rod_55kN.toml, finite_strain) with contact on and
// off (contact.enabled=false, the same bodies), at l0 = 2, 1, 0.5 mm and each
// thread count, from rest: the contact pass over the surface particles and
// their Verlet lists, without rebuilds (a run's rebuilds and its compressed
// phases are in run.json's "contact" phase; docs/contact.md has both).
#include <fmt/format.h>

#include <chrono>

#include "bench/bench_support.hpp"
#include "bench/registry.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid::bench {
namespace {

void run_contact_step(benchmark::State& state, long l0_um, bool contact, int threads) {
  set_thread_count(threads);
  Simulation sim(load_case(std::string(MPSOLID_SOURCE_DIR) + "/cases/shock_rod_55kN.toml",
                           {fmt::format("l0={}", static_cast<double>(l0_um) * 1e-6),
                            fmt::format("contact.enabled={}", contact)}));
  const int steps = repeats_for(sim.particles().size());
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    sim.advance(steps);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count() / steps);
  }
  const ContactState& c = sim.state().contact;
  state.counters["candidates"] = static_cast<double>(c.size());
  state.counters["list_entries"] = static_cast<double>(c.partner.size());
  state.counters["particles"] = static_cast<double>(sim.particles().size());
}

}  // namespace

void register_contact_benchmarks() {
  for (long l0 : {2000L, 1000L, 500L})
    for (bool contact : {false, true})
      for (int threads : bench_threads())
        benchmark::RegisterBenchmark(
            fmt::format("step_contact/finite_strain_55kN/l0_um:{}/"
                        "contact:{}/threads:{}",
                        l0, int{contact}, threads)
                .c_str(),
            [=](benchmark::State& st) { run_contact_step(st, l0, contact, threads); })
            ->UseManualTime()
            ->MinTime(kPerCallMinTime);
}

}  // namespace mpsolid::bench
