#include "src/solver/distributed_step.hpp"

#include <chrono>
#include <stdexcept>
#include <variant>

namespace mpsolid {

Decomposition decompose_state(const SolverState& global, int ranks) {
  // Rigid and loaded bodies stay on one rank (their sums run over all of them).
  std::vector<Range> whole;
  for (const RigidBody& b : global.rigid_bodies) whole.push_back(b.range);
  for (const StepLoad& l : global.loads) whole.push_back(l.range);
  return decompose(global.bonds, ranks, whole);
}

RankPart make_rank_part(const CaseSpec& spec, LocalPart local) {
  RankPart part;
  part.layout = std::move(local.layout);
  part.halo = std::move(local.halo);
  part.local = std::move(local.state);
  part.contact = make_rank_contact(part.local, part.layout, local.decomposition, part.halo);
  part.model = make_model(spec.model, part.local.particles, part.local.bonds, spec.model_options,
                          part.layout.owned);
  return part;
}

RankPart make_rank_part(const CaseSpec& spec, const SolverState& global,
                        const Communicator& world) {
  return make_rank_part(spec,
                        local_part(global, decompose_state(global, world.size()), world.rank()));
}

void advance_rank_part(RankPart& part, const Communicator& world, double dt, std::int64_t steps) {
  if (part.local.contact.enabled())
    rebuild_rank_contact(part.contact, part.local, part.layout, world, part.halo_cost);
  std::visit(
      [&](auto& m) {
        if constexpr (kDecomposable<std::decay_t<decltype(m)>>)
          advance_decomposed(m, part.local, part.layout, part.halo, part.contact, world, dt, steps,
                             part.halo_cost, part.times);
      },
      part.model);
}

}  // namespace mpsolid
