#include "src/solver/split_rigid_bodies.hpp"

#include <algorithm>
#include <stdexcept>

#include "src/distributed/ordered_sum_parts.hpp"

namespace mpsolid {

std::vector<SplitRigidBody> split_rigid_bodies(const CaseSpec& spec,
                                               const std::vector<Range>& body_ranges,
                                               const Decomposition& d,
                                               const std::vector<RigidBody>& mine) {
  std::vector<SplitRigidBody> split;
  for (std::size_t b = 0; b < spec.bodies.size() && b < body_ranges.size(); ++b) {
    if (spec.bodies[b].kind != Kind::rigid || d.owners_of(body_ranges[b]).size() < 2) continue;
    SplitRigidBody s{spec.bodies[b].name, body_ranges[b], -1};
    const auto at = std::find_if(mine.begin(), mine.end(),
                                 [&](const RigidBody& r) { return r.name == spec.bodies[b].name; });
    if (at != mine.end()) s.local = at - mine.begin();
    split.push_back(s);
  }
  return split;
}

void project_split_rigid_bodies(const std::vector<SplitRigidBody>& split, SolverState& s,
                                const LocalLayout& layout, const Decomposition& d,
                                const RankGroup& world, HaloCost& cost, double t, double dt,
                                bool with_rotation) {
  using Part = OrderedSumPart<kProjectionSums>;
  // This rank's chunk sums of each body's projection, shared chunks finished.
  std::vector<double> mine{0.0};  // after their count
  for (const SplitRigidBody& b : split) {
    Part part;
    if (b.local >= 0) {
      const ProjectionTerms term(s.particles, s.rigid_bodies[static_cast<std::size_t>(b.local)],
                                 with_rotation);
      part = ordered_sum_part<kProjectionSums>(
          b.global.begin, b.global.end, layout.owned_pieces,
          [&](std::size_t g) { return term(layout.local_of_owned(g)); });
    }
    finish_shared_chunks(part, b.global.begin, b.global.end, d, world).append_to(mine);
  }
  mine[0] = static_cast<double>(mine.size() - 1);
  std::vector<double> all;
  {
    CommunicationTime time(cost);
    all = world.all_gather(mine);
  }
  HaloTally& tally = cost.tally("rigid bodies");
  std::vector<std::vector<Part>> parts(split.size());
  std::size_t at = 0;
  for (int r = 0; r < world.size(); ++r) {
    const auto n = static_cast<std::size_t>(all.at(at++));
    if (r != world.rank()) tally.received(8 * (n + 1));
    const std::size_t end = at + n;
    for (std::vector<Part>& body : parts) body.push_back(Part::read(all, at));
    if (at != end) throw std::runtime_error("a rank's split rigid bodies: a message out of step");
  }
  for (std::size_t k = 0; k < split.size(); ++k)
    if (split[k].local >= 0)
      advance_rigid_body(s.particles, s.rigid_bodies[static_cast<std::size_t>(split[k].local)],
                         combine_ordered_sum(parts[k]), t, dt, with_rotation);
}

}  // namespace mpsolid
