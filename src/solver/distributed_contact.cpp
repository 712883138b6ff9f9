#include "src/solver/distributed_contact.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"

namespace mpsolid {

namespace {
// Every moving candidate's position from its owner: the ranks' own moving
// candidates, gathered in rank order, put in candidate order.
void gather_candidate_positions(const RankContact& rc, ContactState& c, ParticleStore& p,
                                const RankGroup& world, HaloCost& cost) {
  CommunicationTime t(cost);
  // x, y (and z in space) per candidate.
  std::vector<std::vector<double>*> axes = {&p.x, &p.y};
  if (p.dimension == 3) axes.push_back(&p.z);
  const std::size_t n = axes.size();
  std::vector<double> mine;
  for (const Range run : rc.owned())
    for (std::size_t a = run.begin; a < run.end; ++a)
      for (const std::vector<double>* axis : axes) mine.push_back((*axis)[c.candidates[a]]);
  cost.bytes_sent += 8.0 * static_cast<double>(mine.size());
  const std::vector<double> gathered = world.all_gather(mine);
  cost.tally("contact positions").received(8 * (gathered.size() - mine.size()));
  if (gathered.size() != n * (c.size() - c.first_moving))
    throw std::logic_error("contact: the ranks' candidates do not cover the moving ones");
  const std::vector<double> all = in_candidate_order(rc, gathered, n);
  for (std::size_t a = c.first_moving; a < c.size(); ++a)
    for (std::size_t k = 0; k < n; ++k)
      (*axes[k])[c.candidates[a]] = all[n * (a - c.first_moving) + k];
}

// The contact halo of the current list: what this rank needs (partners of
// its candidates it neither owns nor gets from the bond halo, walls aside),
// asked of their owners; what the others ask of it.
LocalHalo plan_contact_halo(const RankContact& rc, const ContactState& c, const ParticleStore& p,
                            const LocalLayout& layout, const RankGroup& world, HaloCost& cost) {
  std::vector<std::uint32_t> need;  // global storage indices
  for (const Range run : rc.owned())
    for (std::size_t a = run.begin; a < run.end; ++a)
      for (std::uint32_t k = c.offsets[a]; k < c.offsets[a + 1]; ++k) {
        const std::uint32_t j = c.partner[k];
        if ((j >= layout.owned.begin && j < layout.owned.end) || p.kind[j] == Kind::wall ||
            std::binary_search(rc.bond_ghosts.begin(), rc.bond_ghosts.end(), j))
          continue;
        need.push_back(layout.global_of[j]);
      }
  std::sort(need.begin(), need.end());
  need.erase(std::unique(need.begin(), need.end()), need.end());
  // Every rank's request, [count, indices...], in rank order.
  std::vector<double> request{static_cast<double>(need.size())};
  for (const std::uint32_t g : need) request.push_back(static_cast<double>(g));
  std::vector<double> all;
  {
    CommunicationTime t(cost);
    cost.bytes_sent += 8.0 * static_cast<double>(request.size());
    all = world.all_gather(request);
  }
  cost.tally("contact requests").received(8 * (all.size() - request.size()));
  const int me = world.rank();
  std::vector<std::vector<std::uint32_t>> send(static_cast<std::size_t>(world.size())),
      receive(send.size());
  std::size_t at = 0;
  for (int r = 0; r < world.size(); ++r) {
    const auto count = static_cast<std::size_t>(all.at(at++));
    for (std::size_t k = 0; k < count; ++k) {
      const auto g = static_cast<std::uint32_t>(all.at(at++));
      const int owner = rc.decomposition.owner_of(g);
      const auto local = static_cast<std::uint32_t>(layout.local_of(g));
      if (r == me)
        receive[static_cast<std::size_t>(owner)].push_back(local);
      else if (owner == me)
        send[static_cast<std::size_t>(r)].push_back(local);
    }
  }
  LocalHalo halo;
  for (int r = 0; r < world.size(); ++r) {
    const auto k = static_cast<std::size_t>(r);
    if (send[k].empty() && receive[k].empty()) continue;
    halo.peers.push_back(r);
    halo.send.push_back(std::move(send[k]));
    halo.receive.push_back(std::move(receive[k]));
  }
  return halo;
}
}  // namespace

std::vector<double> in_candidate_order(const RankContact& rc, const std::vector<double>& by_rank,
                                       std::size_t width) {
  std::size_t first = std::numeric_limits<std::size_t>::max(), count = 0;
  for (const auto& runs : rc.moving_by_rank)
    for (const Range run : runs) {
      first = std::min(first, run.begin);
      count += run.size();
    }
  if (by_rank.size() != width * count)
    throw std::logic_error("contact: values not one per moving candidate");
  std::vector<double> out(by_rank.size());
  auto from = by_rank.begin();
  for (const auto& runs : rc.moving_by_rank)
    for (const Range run : runs) {
      std::copy_n(from, width * run.size(),
                  out.begin() + static_cast<long>(width * (run.begin - first)));
      from += static_cast<long>(width * run.size());
    }
  return out;
}

RankContact make_rank_contact(const SolverState& s, const LocalLayout& layout,
                              const Decomposition& d, const LocalHalo& bond_halo) {
  RankContact rc;
  rc.decomposition = d;
  const ContactState& c = s.contact;
  // Each moving candidate's owner, from its storage index: runs per rank.
  rc.moving_by_rank.resize(static_cast<std::size_t>(d.ranks()));
  for (std::size_t a = c.first_moving; a < c.size(); ++a) {
    std::vector<Range>& runs =
        rc.moving_by_rank[static_cast<std::size_t>(d.owner_of(layout.global_of[c.candidates[a]]))];
    if (!runs.empty() && runs.back().end == a)
      ++runs.back().end;
    else
      runs.push_back({a, a + 1});
  }
  if (!layout.owned.empty()) rc.rank = d.owner_of(layout.global_of[layout.owned.begin]);
  for (const auto& list : bond_halo.receive)
    rc.bond_ghosts.insert(rc.bond_ghosts.end(), list.begin(), list.end());
  std::sort(rc.bond_ghosts.begin(), rc.bond_ghosts.end());
  return rc;
}

void rebuild_rank_contact(RankContact& rc, SolverState& s, const LocalLayout& layout,
                          const RankGroup& world, HaloCost& cost) {
  ContactState& c = s.contact;
  gather_candidate_positions(rc, c, s.particles, world, cost);
  build_contact_list(c, s.particles, s.bonds);
  rc.halo = plan_contact_halo(rc, c, s.particles, layout, world, cost);
}

void rank_contact_pass(RankContact& rc, SolverState& s, const LocalLayout& layout,
                       const RankGroup& world, std::int64_t step, HaloCost& cost) {
  ContactState& c = s.contact;
  ParticleStore& p = s.particles;
  if (p.dimension == 3)
    exchange_halo(world, rc.halo, "contact", {field_of(p.x), field_of(p.y), field_of(p.z)}, cost);
  else
    exchange_halo(world, rc.halo, "contact", {field_of(p.x), field_of(p.y)}, cost);
  for (const Range run : rc.owned()) compute_contact_forces(c, p, run, step);
  std::int64_t stale = 0;
  {
    CommunicationTime t(cost);
    stale = world.max(c.stale.step.load(std::memory_order_relaxed) == step ? 1 : 0);
  }
  HaloTally& staleness = cost.tally("contact staleness");
  for (int r = 1; r < world.size(); ++r) staleness.received(8);
  if (stale == 0) return;
  rebuild_rank_contact(rc, s, layout, world, cost);
  for (const Range run : rc.owned()) compute_contact_forces(c, p, run, step);
}

}  // namespace mpsolid
