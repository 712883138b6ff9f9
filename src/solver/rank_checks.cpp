#include "src/solver/rank_checks.hpp"

#include <algorithm>
#include <stdexcept>

#include "src/core/loads.hpp"
#include "src/distributed/state_slice.hpp"

namespace mpsolid {

namespace {
constexpr double kNone = -1.0;  // no such particle on this rank

void append_list(const std::vector<double>& values, std::vector<double>& out) {
  out.push_back(static_cast<double>(values.size()));
  out.insert(out.end(), values.begin(), values.end());
}
std::vector<double> read_list(const std::vector<double>& in, std::size_t& at) {
  if (at >= in.size()) throw std::runtime_error("a rank's check cut short");
  const auto count = static_cast<std::size_t>(in[at++]);
  if (at + count > in.size()) throw std::runtime_error("a rank's check cut short");
  std::vector<double> values(in.begin() + static_cast<long>(at),
                             in.begin() + static_cast<long>(at + count));
  at += count;
  return values;
}
}  // namespace

void append_rank_check(const RankPart& part, const RankGroup& world, std::vector<double>& out) {
  const ParticleStore& p = part.local.particles;
  const LocalLayout& layout = part.layout;
  const Range owned = layout.owned;
  const auto global_index = [&](std::size_t i) { return static_cast<double>(layout.global_of[i]); };
  // Its share of the motion sums, the chunks it shares finished on the ranks.
  finish_shared_chunks(
      ordered_sum_part<kMotionSums>(
          part.moving_begin, part.particles_in_run, layout.owned_pieces,
          [&](std::size_t g) { return motion_terms(p, layout.local_of_owned(g)); }),
      part.moving_begin, part.particles_in_run, part.decomposition, world)
      .append_to(out);
  // The first non-finite particle, as check_finite scans.
  double bad = kNone;
  for (std::size_t i = owned.begin; i < owned.end && bad == kNone; ++i)
    if (!state_is_finite(p, i)) bad = global_index(i);
  out.push_back(bad);
  // The first fastest moving particle, as check_speed scans.
  const Range moving = p.moving();
  double fastest2 = -1.0, fastest = kNone;
  for (std::size_t i = std::max(moving.begin, owned.begin); i < std::min(moving.end, owned.end);
       ++i) {
    const double s2 = speed_squared(p, i);
    if (s2 > fastest2) {
      fastest2 = s2;
      fastest = global_index(i);
    }
  }
  out.push_back(fastest);
  out.push_back(fastest2);
  // Its loads' work and its rigid bodies' drivers' work, in their order,
  // then their fields.
  std::vector<double> work;
  for (const StepLoad& load : part.local.loads)
    if (!load.is_pressure()) work.push_back(load_work(p, load));
  append_list(work, out);
  work.clear();
  for (const RigidBody& body : part.local.rigid_bodies) work.push_back(body.work);
  append_list(work, out);
  StateSlice::append_items(part.local, owned, out);
  // Its part of each elastic body's extent.
  for (const Range body : part.extent_ranges) {
    const std::array<double, 6> extent = extent_of(p, layout.owned_within(body));
    out.insert(out.end(), extent.begin(), extent.end());
  }
  // The probes it owns: their number in the case and position.
  std::vector<double> probes;
  for (std::size_t k = 0; k < part.probes.size(); ++k) {
    const std::size_t g = part.probes[k];
    if (!layout.owns(g)) continue;
    const std::array<double, 3> at = position_of(p, layout.local_of_owned(g));
    probes.insert(probes.end(), {static_cast<double>(k), at[0], at[1], at[2]});
  }
  append_list(probes, out);
  // The current positions of the pressure nodes it hosts (every part holds
  // every node; each positions those whose host it owns).
  std::vector<double> nodes;
  append_hosted_node_positions(p, part.local.loads, nodes);
  append_list(nodes, out);
  // Its own moving contact candidates' positions, in candidate order, and
  // the first step its contact pass found a pair too close.
  const ContactState& c = part.local.contact;
  std::vector<double> candidates;
  for (const Range run : part.contact.owned())
    for (std::size_t a = run.begin; a < run.end; ++a) {
      const std::array<double, 3> at = position_of(p, c.candidates[a]);
      candidates.insert(candidates.end(), at.begin(), at.begin() + (p.dimension == 3 ? 3 : 2));
    }
  append_list(candidates, out);
  out.push_back(static_cast<double>(c.too_close.step.load()));
}

void RankChecks::read(const std::vector<double>& in, std::size_t& at, SolverState& global,
                      const std::vector<Range>& owned) {
  motion_.push_back(OrderedSumPart<kMotionSums>::read(in, at));
  if (at + 3 > in.size()) throw std::runtime_error("a rank's check cut short");
  const double bad = in[at++];
  // The first in storage order over the ranks (a rank's own is its first).
  if (bad != kNone &&
      (figures_.finite.ok || static_cast<std::size_t>(bad) < figures_.finite.particle))
    figures_.finite = non_finite_verdict(static_cast<std::size_t>(bad));
  const double fastest = in[at++], fastest2 = in[at++];
  if (fastest != kNone && (fastest2 > figures_.fastest.speed2 ||
                           (fastest2 == figures_.fastest.speed2 &&
                            static_cast<std::size_t>(fastest) < figures_.fastest.particle)))
    figures_.fastest = {static_cast<std::size_t>(fastest), fastest2};
  load_work_.push_back(read_list(in, at));
  body_work_.push_back(read_list(in, at));
  StateSlice::read_items(global, owned, in, at);
  std::vector<std::array<double, 6>>& extents = figures_.readings.extents;
  for (std::size_t b = 0; b < elastic_bodies_; ++b) {
    if (at + 6 > in.size()) throw std::runtime_error("a rank's check cut short");
    std::array<double, 6> part;
    std::copy_n(in.begin() + static_cast<long>(at), 6, part.begin());
    at += 6;
    if (extents.size() < elastic_bodies_)  // the first rank's
      extents.push_back(part);
    else
      widen(extents[b], part);
  }
  figures_.readings.probes.resize(global.probes.size());
  const std::vector<double> probes = read_list(in, at);
  for (std::size_t k = 0; k + 4 <= probes.size(); k += 4)
    figures_.readings.probes.at(static_cast<std::size_t>(probes[k])) = {
        probes[k + 1], probes[k + 2], probes[k + 3]};
  const std::vector<double> nodes = read_list(in, at);
  pressure_nodes_.insert(pressure_nodes_.end(), nodes.begin(), nodes.end());
  // In rank order (in_candidate_order puts them in candidate order).
  const std::vector<double> candidates = read_list(in, at);
  figures_.candidate_positions.insert(figures_.candidate_positions.end(), candidates.begin(),
                                      candidates.end());
  if (at >= in.size()) throw std::runtime_error("a rank's check cut short");
  const auto too_close = static_cast<std::int64_t>(in[at++]);
  if (too_close >= 0 && (figures_.too_close < 0 || too_close < figures_.too_close))
    figures_.too_close = too_close;
}

CheckFigures RankChecks::finish(const SolverState& global, const Decomposition& d,
                                const RankFields& fields) const {
  CheckFigures f = figures_;
  f.diagnostics = motion_from_sums(combine_ordered_sum(motion_), std::max(f.fastest.speed2, 0.0));
  f.diagnostics.strain_energy = fields.strain_energy;
  f.integrity = fields.integrity;
  // Each load or body is its owner's (kept whole on one rank), in the
  // owner's order: the whole state's sums in its order.
  std::vector<std::size_t> next(static_cast<std::size_t>(d.ranks()), 0);
  const auto take = [&](const std::vector<std::vector<double>>& lists, Range range) {
    const auto r = static_cast<std::size_t>(d.owner_of(range.begin));
    return lists.at(r).at(next[r]++);
  };
  // Every node of each pressure load from the rank that hosts it (rank 0's
  // loads are every part's: the same running step).
  std::vector<std::vector<double>> node_xyz;
  for (const StepLoad& load : global.loads)
    if (load.is_pressure()) node_xyz.emplace_back(3 * load.surface.nodes(), 0.0);
  for (std::size_t k = 0; k + 5 <= pressure_nodes_.size(); k += 5) {
    std::vector<double>& xyz = node_xyz.at(static_cast<std::size_t>(pressure_nodes_[k]));
    const auto node = static_cast<std::size_t>(pressure_nodes_[k + 1]);
    std::copy_n(pressure_nodes_.begin() + static_cast<long>(k + 2), 3,
                xyz.begin() + static_cast<long>(3 * node));
  }
  double work = 0.0;
  std::size_t pressures = 0;
  for (const StepLoad& load : global.loads) {
    f.readings.load_work.push_back(load.is_pressure()
                                       ? pressure_work_at(load, node_xyz.at(pressures++))
                                       : take(load_work_, load.range));
    work += f.readings.load_work.back();
  }
  std::fill(next.begin(), next.end(), 0);
  // A split rigid body's work is every one of its ranks' (the same): its
  // first particle's owner's counted, the others' passed over.
  for (const RigidBody& body : global.rigid_bodies) {
    const double w = take(body_work_, body.range);
    for (const int r : d.owners_of(body.range))
      if (r != d.owner_of(body.range.begin)) next[static_cast<std::size_t>(r)]++;
    work += w;
  }
  f.diagnostics.external_work = work;
  return f;
}

}  // namespace mpsolid
