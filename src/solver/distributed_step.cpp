#include "src/solver/distributed_step.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <variant>

#include "src/core/ordered_sum.hpp"

namespace mpsolid {

Decomposition decompose_state(const SolverState& global, int ranks,
                              const std::vector<double>* cost) {
  // Rigid bodies and bodies under a force stay on one rank (their sums run
  // over all of them); a pressure's body may be split (its nodes are shared).
  std::vector<Range> whole;
  for (const RigidBody& b : global.rigid_bodies) whole.push_back(b.range);
  for (const StepLoad& l : global.loads)
    if (!l.is_pressure()) whole.push_back(l.range);
  return cost ? decompose_costs(*cost, ranks, whole) : decompose(global.bonds, ranks, whole);
}

std::vector<double> gather_shared_values(const RankGroup& world, const std::vector<double>& mine,
                                         HaloCost& cost, const char* what) {
  CommunicationTime t(cost);
  // Each rank's values after their count, so that each message is tallied.
  std::vector<double> framed{static_cast<double>(mine.size())};
  framed.insert(framed.end(), mine.begin(), mine.end());
  const std::vector<double> all = world.all_gather(framed);
  HaloTally& tally = cost.tally(what);
  std::vector<double> values;
  std::size_t at = 0;
  for (int r = 0; r < world.size(); ++r) {
    const auto n = static_cast<std::size_t>(all.at(at));
    if (r != world.rank()) tally.received(8 * (n + 1));
    values.insert(values.end(), all.begin() + static_cast<long>(at + 1),
                  all.begin() + static_cast<long>(at + 1 + n));
    at += n + 1;
  }
  return values;
}

namespace {
// The owned particles bonded only to owned ones: [a, b) with every owned
// particle bonded below the owned range before a and every one bonded
// above it from b on (storage is slabs of rows: these are the rows at
// the cuts).
Range bonded_to_owned_only(const BondTable& bonds, Range owned) {
  std::size_t a = owned.begin, b = owned.end;
  for (std::size_t i = owned.begin; i < owned.end; ++i)
    for (std::uint32_t k = bonds.begin(i); k < bonds.end(i); ++k) {
      const std::size_t j = bonds.neighbor[k];
      if (j < owned.begin) a = std::max(a, i + 1);
      if (j >= owned.end) b = std::min(b, i);
    }
  return {std::min(a, b), b};
}
}  // namespace

RankPart make_rank_part(const CaseSpec& spec, LocalPart local) {
  RankPart part;
  part.layout = std::move(local.layout);
  part.halo = std::move(local.halo);
  part.local = std::move(local.state);
  part.particles_in_run = local.decomposition.starts.back();
  part.decomposition = local.decomposition;
  part.moving_begin = local.moving_begin;
  for (std::size_t b = 0; b < spec.bodies.size() && b < local.body_ranges.size(); ++b)
    if (spec.bodies[b].kind == Kind::elastic) part.extent_ranges.push_back(local.body_ranges[b]);
  part.probes = std::move(local.probes);
  part.body_ranges = local.body_ranges;
  part.split_rigid =
      split_rigid_bodies(spec, part.body_ranges, part.decomposition, part.local.rigid_bodies);
  part.contact = make_rank_contact(part.local, part.layout, local.decomposition, part.halo);
  part.local.contact.order_by_storage();
  part.model = make_model(spec.model, part.local.particles, part.local.bonds, spec.model_options,
                          part.layout.owned);
  part.bonded_to_owned_only = bonded_to_owned_only(part.local.bonds, part.layout.owned);
  return part;
}

RankPart make_rank_part(const CaseSpec& spec, const SolverState& global, const RankGroup& world) {
  return make_rank_part(spec,
                        local_part(global, decompose_state(global, world.size()), world.rank()));
}

void advance_rank_part(RankPart& part, const RankGroup& world, double dt, std::int64_t steps) {
  if (part.local.contact.enabled())
    rebuild_rank_contact(part.contact, part.local, part.layout, world, part.halo_cost);
  OverRanks place(part, world);
  BodyKicks kicks(part.local.rigid_bodies.size());
  for (const SplitRigidBody& b : part.split_rigid)
    if (b.local >= 0) kicks.mark_split(static_cast<std::size_t>(b.local));
  std::visit([&](auto& model) { steps_in_order(model, part.local, dt, steps, kicks, place); },
             part.model);
  part.local.step += steps;
}

void append_rank_fields(RankPart& part, const RankGroup& world, const IntegrityLimits& limits,
                        std::vector<double>& out, bool arrays) {
  SolverState& s = part.local;
  ParticleStore& p = s.particles;
  const LocalLayout& layout = part.layout;
  const Range owned = layout.owned;
  OverRanks place(part, world, OverRanks::Timing::off);
  std::visit(
      [&](auto& model) {
        strain_fields(model, s, place);
        if (arrays) {
          out.insert(out.end(), p.strain.begin() + static_cast<long>(owned.begin),
                     p.strain.begin() + static_cast<long>(owned.end));
          out.insert(out.end(), p.pressure.begin() + static_cast<long>(owned.begin),
                     p.pressure.begin() + static_cast<long>(owned.end));
        }
        // The owned pieces' share of the serial chunks (a cut may fall
        // inside one), the chunks it shares finished on the ranks.
        finish_shared_chunks(
            ordered_sum_part<1>(0, part.particles_in_run, layout.owned_pieces,
                                [&](std::size_t g) {
                                  return std::array<double, 1>{model.particle_strain_energy(
                                      p, s.bonds, layout.local_of_owned(g))};
                                }),
            0, part.particles_in_run, part.decomposition, world)
            .append_to(out);
        const IntegrityReport r = model.check_integrity(p, s.bonds, limits, owned);
        out.push_back(r.value);
        out.push_back(owned.empty() ? 0.0 : static_cast<double>(layout.global_of[r.particle]));
        out.push_back(owned.empty() ? 0.0 : static_cast<double>(layout.global_of[r.neighbor]));
        out.push_back(r.failed ? 1.0 : 0.0);
        out.push_back(static_cast<double>(r.criterion.size()));
        for (const char c : r.criterion) out.push_back(static_cast<double>(c));
      },
      part.model);
}

void read_rank_fields(const std::vector<double>& in, std::size_t& at,
                      const std::vector<Range>& owned, ParticleStore& global,
                      std::vector<OrderedSumPart<1>>& energy_parts, RankFields& fields,
                      bool arrays) {
  if (arrays)
    for (std::vector<double>* field : {&global.strain, &global.pressure})
      for (const Range r : owned) {
        std::copy_n(in.begin() + static_cast<long>(at), r.size(),
                    field->begin() + static_cast<long>(r.begin));
        at += r.size();
      }
  energy_parts.push_back(OrderedSumPart<1>::read(in, at));
  IntegrityReport r;
  r.value = in[at++];
  r.particle = static_cast<std::size_t>(in[at++]);
  r.neighbor = static_cast<std::size_t>(in[at++]);
  r.failed = in[at++] != 0.0;
  r.criterion.resize(static_cast<std::size_t>(in[at++]));
  for (char& c : r.criterion) c = static_cast<char>(in[at++]);
  // The first smallest in storage order, as the serial scan finds it.
  const IntegrityReport& worst = fields.integrity;
  const bool any = std::any_of(owned.begin(), owned.end(), [](Range o) { return !o.empty(); });
  if (any && (worst.criterion.empty() || r.value < worst.value ||
              (r.value == worst.value && r.particle < worst.particle)))
    fields.integrity = r;
}

}  // namespace mpsolid
