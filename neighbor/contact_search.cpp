#include "neighbor/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
// Candidates a and b may touch: not in one group, not bonded. (A row is
// searched whole: on a rank's part cut in pieces its partners need not
// ascend in local index.)
bool may_touch(const ContactState& c, const BondTable& bonds, std::size_t a, std::size_t b) {
  if (c.group[a] != kNoContactGroup && c.group[a] == c.group[b]) return false;
  const std::size_t i = c.candidates[a];
  const auto row = bonds.neighbor.begin();
  return std::find(row + bonds.begin(i), row + bonds.end(i), c.candidates[b]) == row + bonds.end(i);
}

// The candidates' current positions and their pairs closer than `cutoff`
// (candidate indices, compressed rows, both ends, ascending: candidates are
// in the run's storage order, so this is ascending storage index too). A
// candidate whose position is not finite has no pairs: the run's finite
// check reports it; the search must not fail first.
struct NearCandidates {
  std::vector<double> x, y, z;  // z in space only
  NeighborLists lists;
  double squared_distance(std::size_t a, std::size_t b) const {
    double d2 = mpsolid::squared_distance(x[a], y[a], x[b], y[b]);
    if (!z.empty()) d2 += (z[a] - z[b]) * (z[a] - z[b]);
    return d2;
  }
};
NearCandidates near_candidates(const ContactState& c, const ParticleStore& p, double cutoff) {
  NearCandidates near;
  const bool space = p.dimension == 3;
  std::vector<std::uint32_t> finite;  // the candidates searched, and their positions
  std::vector<double> fx, fy, fz;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const double x = p.x[c.candidates[a]], y = p.y[c.candidates[a]];
    const double z = space ? p.z[c.candidates[a]] : 0.0;
    near.x.push_back(x);
    near.y.push_back(y);
    if (space) near.z.push_back(z);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
    finite.push_back(static_cast<std::uint32_t>(a));
    fx.push_back(x);
    fy.push_back(y);
    if (space) fz.push_back(z);
  }
  const NeighborLists found = find_neighbors_sparse_cells({fx, fy, fz}, cutoff);
  near.lists.offsets.assign(c.size() + 1, 0);
  std::size_t next = 0;  // the next finite candidate
  for (std::size_t a = 0; a < c.size(); ++a) {
    if (next < finite.size() && finite[next] == a) {
      for (std::uint32_t k = found.offsets[next]; k < found.offsets[next + 1]; ++k)
        near.lists.indices.push_back(finite[found.indices[k]]);
      ++next;
    }
    near.lists.offsets[a + 1] = static_cast<std::uint32_t>(near.lists.indices.size());
  }
  return near;
}

// Those of the pairs that may touch.
NeighborLists touching_pairs(const ContactState& c, const ParticleStore& p, const BondTable& bonds,
                             double cutoff) {
  const std::size_t n = c.size();
  const NeighborLists near = near_candidates(c, p, cutoff).lists;
  NeighborLists out;
  out.offsets.assign(n + 1, 0);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::uint32_t k = near.offsets[a]; k < near.offsets[a + 1]; ++k) {
      const std::uint32_t b = near.indices[k];
      if (may_touch(c, bonds, a, b)) out.indices.push_back(b);
    }
    out.offsets[a + 1] = static_cast<std::uint32_t>(out.indices.size());
  }
  return out;
}
}  // namespace

void build_contact_list(ContactState& c, const ParticleStore& p, const BondTable& bonds) {
  const ContactParameters& k = c.parameters;
  NeighborLists pairs = touching_pairs(c, p, bonds, k.distance + k.skin);
  c.offsets = std::move(pairs.offsets);
  c.partner = std::move(pairs.indices);
  for (std::uint32_t& b : c.partner) b = c.candidates[b];
  c.built_x.resize(c.size());
  c.built_y.resize(c.size());
  for (std::size_t a = 0; a < c.size(); ++a) {
    c.built_x[a] = p.x[c.candidates[a]];
    c.built_y[a] = p.y[c.candidates[a]];
  }
  if (p.dimension == 3) {
    c.built_z.resize(c.size());
    for (std::size_t a = 0; a < c.size(); ++a) c.built_z[a] = p.z[c.candidates[a]];
  }
  ++c.rebuilds;
}

void refresh_contact_list(ContactState& c, const ParticleStore& p, const BondTable& bonds) {
  for (std::size_t a = c.first_moving; a < c.size(); ++a)
    if (c.moved_past_half_skin(p, a)) {
      build_contact_list(c, p, bonds);
      return;
    }
}

ClosestContact closest_contact(const ContactState& c, const ParticleStore& p,
                               const BondTable& bonds, double cutoff) {
  ClosestContact best;
  if (!c.enabled()) return best;
  const NearCandidates near = near_candidates(c, p, cutoff);
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::uint32_t k = near.lists.offsets[a]; k < near.lists.offsets[a + 1]; ++k) {
      const std::uint32_t b = near.lists.indices[k];
      if (b < a) continue;  // each pair once, from its lower end
      const double d2 = near.squared_distance(a, b);
      // Only a pair that would be the closest is checked for a bond.
      if (d2 < best_d2 && may_touch(c, bonds, a, b)) {
        best_d2 = d2;
        best = {true, std::sqrt(d2), c.candidates[a], c.candidates[b]};
      }
    }
  return best;
}

}  // namespace mpsolid
