#include "tests/support/serial_bits.hpp"

#include <cstring>
#include <utility>

#include "src/solver/distributed_step.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/thread_team.hpp"

namespace mpsolid::testing {

namespace {
bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
}  // namespace

std::vector<std::string> serial_bits_failures(
    const CaseSpec& spec, std::int64_t steps,
    const std::function<Decomposition(const SolverState&)>& cut_of) {
  Simulation serial(spec);
  const CaseSpec& run = serial.spec();  // its step fixed
  const SolverState start = serial.state();
  const Decomposition d = cut_of(start);
  serial.advance(steps);
  const SolverState& want = serial.state();
  const ParticleStore& p = want.particles;
  std::vector<std::string> failures(static_cast<std::size_t>(d.ranks()));
  as_ranks(d.ranks(), [&](const RankGroup& world, int me) {
    std::string& failure = failures[static_cast<std::size_t>(me)];
    const auto fail = [&](const std::string& what) {
      if (failure.empty()) failure = "rank " + std::to_string(me) + ": " + what;
    };
    RankPart part = make_rank_part(run, local_part(start, d, me));
    advance_rank_part(part, world, run.dt, steps);
    const ParticleStore& got = part.local.particles;
    for (std::size_t k = part.layout.owned.begin; k < part.layout.owned.end; ++k) {
      const std::size_t g = part.layout.global_of[k];
      std::vector<std::pair<const std::vector<double>*, const std::vector<double>*>> arrays{
          {&got.x, &p.x}, {&got.y, &p.y}, {&got.vx, &p.vx}, {&got.vy, &p.vy}};
      if (got.dimension == 3) arrays.insert(arrays.end(), {{&got.z, &p.z}, {&got.vz, &p.vz}});
      for (const auto& [a, b] : arrays)
        if (!same_bits((*a)[k], (*b)[g])) fail("particle " + std::to_string(g) + " differs");
    }
    for (const RigidBody& body : part.local.rigid_bodies)
      for (const RigidBody& serial_body : want.rigid_bodies) {
        if (serial_body.name != body.name) continue;
        const std::vector<double> a = pose_values(body), b = pose_values(serial_body);
        for (std::size_t v = 0; v < a.size(); ++v)
          if (!same_bits(a[v], b[v])) fail(body.name + "'s pose value " + std::to_string(v));
        if (!same_bits(body.work, serial_body.work)) fail(body.name + "'s work");
      }
  });
  return failures;
}

}  // namespace mpsolid::testing
