#include "src/solver/time_step_choice.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

#include "kernels/model_registry.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/stable_step.hpp"

namespace mpsolid {

namespace {
// Contact stiffens the system only once bodies touch, so its bound is
// added: the largest eigenvalue of a sum is at most the sum of the largest.
StableStepEstimate with_contact(StableStepEstimate e, const CaseSpec& spec,
                                double largest_inv_mass) {
  if (!(e.dt_limit > 0)) return e;
  if (const double contact = contact_omega_squared(spec, largest_inv_mass); contact > 0) {
    e.omega_max = std::sqrt(e.omega_max * e.omega_max + contact);
    e.dt_limit = 2.0 / e.omega_max;
  }
  return e;
}

// A rank's share of the estimate's sums: its owned elastic particles,
// every rank's part of each ordered sum (its chunks' sums, those shared
// with other ranks finished on the ranks) gathered and combined in storage
// order (the one-process bits), the largest value gathered likewise.
struct PartSums {
  const RankGroup& world;
  const LocalLayout& layout;
  const Decomposition& cut;
  Range elastic;            // the owned elastic particles (local indices)
  std::vector<Range> held;  // ... as global storage ranges
  Range global_elastic{};   // every rank's elastic particles (global)

  PartSums(const RankGroup& w, const RankPart& part)
      : world(w), layout(part.layout), cut(part.decomposition) {
    const Range owned = layout.owned, kind = part.local.particles.elastic;
    const std::size_t b = std::clamp(kind.begin, owned.begin, owned.end);
    elastic = {b, std::clamp(kind.end, b, owned.end)};
    // The owned pieces within the owned elastic particles' global span.
    const std::size_t from = elastic.empty() ? 0 : layout.global_of[elastic.begin];
    const std::size_t to = elastic.empty() ? 0 : layout.global_of[elastic.end - 1] + std::size_t{1};
    for (const Range r : layout.owned_pieces)
      if (std::max(r.begin, from) < std::min(r.end, to))
        held.push_back({std::max(r.begin, from), std::min(r.end, to)});
    // The elastic particles are one storage range: its ends over the ranks.
    const std::vector<double> ends =
        world.all_gather({elastic.empty() ? -1.0 : static_cast<double>(from),
                          elastic.empty() ? -1.0 : static_cast<double>(to)});
    bool any = false;
    for (std::size_t r = 0; r + 1 < ends.size(); r += 2) {
      if (ends[r] < 0) continue;
      const auto lo = static_cast<std::size_t>(ends[r]);
      const auto hi = static_cast<std::size_t>(ends[r + 1]);
      global_elastic =
          any ? Range{std::min(global_elastic.begin, lo), std::max(global_elastic.end, hi)}
              : Range{lo, hi};
      any = true;
    }
  }

  template <class Term>
  double sum(Term&& term) const {
    // The chunks it shares finished on the ranks: only chunk sums go round.
    const OrderedSumPart<1> mine = finish_shared_chunks(
        ordered_sum_part<1>(
            global_elastic.begin, global_elastic.end, held,
            [&](std::size_t g) { return std::array<double, 1>{term(layout.local_of_owned(g))}; }),
        global_elastic.begin, global_elastic.end, cut, world);
    std::vector<double> message;
    mine.append_to(message);
    const std::vector<double> all = world.all_gather(message);
    std::vector<OrderedSumPart<1>> parts;
    for (std::size_t at = 0; at < all.size();) parts.push_back(OrderedSumPart<1>::read(all, at));
    return combine_ordered_sum(parts)[0];
  }
  double largest(double mine) const {
    const std::vector<double> all = world.all_gather({mine});
    return *std::max_element(all.begin(), all.end());
  }
};
}  // namespace

StableStepEstimate estimate_case_stable_step(const CaseSpec& spec, const SolverState& s) {
  AnyModel model = make_model(spec.model, s.particles, s.bonds, spec.model_options);
  PhaseTimers scratch;  // the passes are set-up's, not a step's
  OneRank place(scratch);
  const EstimateSums sums{s.particles.elastic};
  const StableStepEstimate e = std::visit(
      [&](auto& m) { return estimate_stable_step(m, s.particles, s.bonds, spec.l0, place, sums); },
      model);
  return with_contact(
      e, spec, largest_contact_inv_mass(spec, s.body_ranges, s.particles, s.particles.all(), 0));
}

StableStepEstimate estimate_part_stable_step(const CaseSpec& spec, RankPart& part,
                                             const RankGroup& world) {
  const HaloCost before = part.halo_cost;
  const PartSums sums(world, part);
  OverRanks place(part, world, OverRanks::Timing::off);
  const StableStepEstimate e = std::visit(
      [&](auto& m) {
        return estimate_stable_step(m, part.local.particles, part.local.bonds, spec.l0, place,
                                    sums);
      },
      part.model);
  double mine = 0;
  for (std::size_t k = 0; k < part.layout.owned_pieces.size(); ++k)
    mine = std::max(
        mine, largest_contact_inv_mass(spec, part.body_ranges, part.local.particles,
                                       part.layout.owned_pieces[k], part.layout.piece_local[k]));
  const double inv_mass = sums.largest(mine);
  part.halo_cost = before;
  return with_contact(e, spec, inv_mass);
}

void choose_time_step(CaseSpec& spec, const StableStepEstimate& estimate) {
  if (!(estimate.dt_limit > 0))
    throw InputError(fmt::format(
        "{}: time.dt = \"auto\" needs elastic particles to estimate the stable step from; "
        "give dt in s",
        spec.source));
  spec.set_auto_time_step(estimate.dt_limit, estimate.omega_max);
}

std::string fixed_time_step_warning(const CaseSpec& spec, const StableStepEstimate& e) {
  if (!(e.dt_limit > 0) || spec.dt <= e.dt_limit) return "";
  return fmt::format(
      "{}: time.dt = {:.6g} s is above the stable step estimated for the {} model on this case, "
      "{:.6g} s (2 / omega_max, {} power iterations): the run will likely go unstable within a "
      "few steps; use time.dt = \"auto\" (time.safety x that estimate) or a dt below it",
      spec.source, spec.dt, spec.model, e.dt_limit, e.iterations);
}

}  // namespace mpsolid
