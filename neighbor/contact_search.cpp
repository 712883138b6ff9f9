#include "neighbor/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
// The candidates' pairs closer than `cutoff` that may touch, as candidate
// indices in compressed rows (both ends, ascending: candidates are sorted by
// storage index, so this is ascending storage index too).
NeighborLists touching_pairs(const ContactState& c, const ParticleStore& p, const BondTable& bonds,
                             double cutoff) {
  const std::size_t n = c.size();
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    x[k] = p.x[c.candidates[k]];
    y[k] = p.y[c.candidates[k]];
  }
  NeighborLists near = find_neighbors_cell_list(x, y, cutoff);
  const auto bonded = [&](std::size_t i, std::size_t j) {
    const auto row = bonds.neighbor.begin();
    return std::binary_search(row + bonds.begin(i), row + bonds.end(i),
                              static_cast<std::uint32_t>(j));
  };
  NeighborLists out;
  out.offsets.assign(n + 1, 0);
  for (std::size_t a = 0; a < n; ++a) {
    for (std::uint32_t k = near.offsets[a]; k < near.offsets[a + 1]; ++k) {
      const std::uint32_t b = near.indices[k];
      const bool same_group = c.group[a] != kNoContactGroup && c.group[a] == c.group[b];
      if (!same_group && !bonded(c.candidates[a], c.candidates[b])) out.indices.push_back(b);
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
  const NeighborLists pairs = touching_pairs(c, p, bonds, cutoff);
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < c.size(); ++a)
    for (std::uint32_t k = pairs.offsets[a]; k < pairs.offsets[a + 1]; ++k) {
      const std::size_t i = c.candidates[a], j = c.candidates[pairs.indices[k]];
      if (j < i) continue;  // each pair once, from its lower end
      const double d2 = squared_distance(p.x[i], p.y[i], p.x[j], p.y[j]);
      if (d2 < best_d2) {
        best_d2 = d2;
        best = {true, std::sqrt(d2), i, j};
      }
    }
  return best;
}

}  // namespace mpsolid
