// Each kernel of the step alone, for every model, on the rod at l0 = 2, 1,
// 0.5, 0.25 mm and each thread count: half angles, strain pass, force/torque
// pass, integration (loads, kick, drift, half angles), rigid-body projection.
// Each runs repeated inside one parallel region, as in the step loop.
#include <fmt/format.h>

#include <algorithm>

#include "bench/bench_support.hpp"
#include "bench/flop_counts.hpp"
#include "bench/registry.hpp"
#include "kernels/model_registry.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/step.hpp"

namespace mpsolid::bench {
namespace {

enum class Kernel { half_angles, strain, forces, integrate, rigid_bodies };

// Bond entries in the rows of a range of particles.
double entries_of(const BondTable& bonds, Range r) {
  return static_cast<double>(bonds.begin(r.end) - bonds.begin(r.begin));
}

void run_kernel(benchmark::State& state, Kernel kernel, const std::string& model_name, long l0_um,
                int threads) {
  set_thread_count(threads);
  Simulation sim(rod(l0_um, model_name));
  sim.advance(10);  // a deformed, rotated state
  SolverState& s = sim.state_to_change();
  ParticleStore& p = s.particles;
  AnyModel any = make_model(model_name, p, s.bonds, sim.spec().model_options);
  const FlopCounts f = flop_counts(model_name);
  const int repeats = repeats_for(p.size());
  double particles = 0, entries = 0, flops = 0;
  std::visit(
      [&](auto& model) {
        constexpr bool rot = std::remove_reference_t<decltype(model)>::uses_rotation;
        model.compute_strain(p, s.bonds, p.all());
        switch (kernel) {
          case Kernel::half_angles:
            time_in_team(state, repeats, [&] { compute_half_angles(p, p.moving()); });
            particles = static_cast<double>(p.moving().size());
            flops = particles * f.half_angles_particle;
            break;
          case Kernel::strain:
            time_in_team(state, repeats, [&] { model.compute_strain(p, s.bonds, p.all()); });
            particles = static_cast<double>(p.size());
            entries = entries_of(s.bonds, p.all());
            flops = entries * f.strain_entry + particles * f.strain_particle;
            break;
          case Kernel::forces:
            time_in_team(state, repeats, [&] { model.compute_forces(p, s.bonds, p.moving()); });
            particles = static_cast<double>(p.moving().size());
            entries = entries_of(s.bonds, p.moving());
            flops = entries * f.force_entry + particles * f.force_particle;
            break;
          case Kernel::integrate: {
            // Zero forces keep the state bounded over millions of calls (the
            // same arithmetic; large angles would slow sin and cos).
            for (auto* v : {&p.fx, &p.fy, &p.torque}) std::fill(v->begin(), v->end(), 0.0);
            // With the rigid plate's projection, as the step does it.
            BodyKicks kicks(s.rigid_bodies.size());
            time_in_team(state, repeats, [&] {
              parallel_blocks(p.moving().begin, p.moving().end, [&](std::size_t b, std::size_t e) {
                integrate_block<rot>(s, sim.spec().dt, s.step, {b, e}, kicks);
              });
            });
            particles = static_cast<double>(p.moving().size());
            flops = particles * f.integrate_particle;
            break;
          }
          case Kernel::rigid_bodies:
            time_in_team(state, repeats, [&] {
              parallel_for(0, s.rigid_bodies.size(), [&](std::size_t k) {
                project_rigid_body(p, s.rigid_bodies[k], 0.0, sim.spec().dt, rot);
              });
            });
            particles = static_cast<double>(p.rigid.size());
            flops = particles * kRigidFlopsPerParticle;
            break;
        }
      },
      any);
  rate_counters(state, particles, entries, flops, threads);
}

}  // namespace

void register_kernel_benchmarks() {
  const std::pair<Kernel, const char*> kernels[] = {{Kernel::half_angles, "half_angles"},
                                                    {Kernel::strain, "strain"},
                                                    {Kernel::forces, "forces"},
                                                    {Kernel::integrate, "integrate"},
                                                    {Kernel::rigid_bodies, "rigid_bodies"}};
  for (const auto& [kernel, kernel_name] : kernels)
    for (const std::string& model : model_names()) {
      if (kernel == Kernel::half_angles && !model_info(model).uses_rotation) continue;
      for (long l0 : kSpacingsUm)
        for (int threads : bench_threads())
          benchmark::RegisterBenchmark(
              fmt::format("kernel/{}/{}/l0_um:{}/threads:{}", kernel_name, model, l0, threads)
                  .c_str(),
              [=, k = kernel](benchmark::State& st) { run_kernel(st, k, model, l0, threads); })
              ->UseManualTime()
              ->MinTime(kPerCallMinTime);
    }
}

}  // namespace mpsolid::bench
