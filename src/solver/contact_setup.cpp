#include "src/solver/contact_setup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "neighbor/contact_search.hpp"

namespace mpsolid {

namespace {
// Walls never move: all of them share one group.
constexpr std::int32_t kWallGroup = -2;

// Lattice offsets (a, b[, c]) != 0 with |(a, b[, c])| < radius from the
// point (u, v[, w]): the bonds of an interior particle when radius = re / l0
// and the point is a site.
int lattice_sites_within(int dimension, double radius, double u = 0, double v = 0, double w = 0,
                         bool skip_origin = true) {
  const int reach = static_cast<int>(std::ceil(radius)) + 1;
  const int reach_z = dimension == 3 ? reach : 0;
  int count = 0;
  for (int c = -reach_z; c <= reach_z; ++c)
    for (int a = -reach; a <= reach; ++a)
      for (int b = -reach; b <= reach; ++b) {
        if (skip_origin && a == 0 && b == 0 && c == 0) continue;
        const double dx = a - u, dy = b - v, dz = dimension == 3 ? c - w : 0.0;
        if (dx * dx + dy * dy + dz * dz < radius * radius) ++count;
      }
  return count;
}

// The most lattice sites (spacing 1) closer than `radius` to any point.
int most_sites_near_a_point(int dimension, double radius) {
  const int samples = dimension == 3 ? 20 : 40;
  const auto at = [&](int s) { return 0.5 * s / samples; };
  int most = 0;
  for (int s = 0; s <= samples; ++s)
    for (int t = 0; t <= s; ++t)  // the cell's symmetric part suffices
      for (int u = 0; u <= (dimension == 3 ? t : 0); ++u)
        most = std::max(most, lattice_sites_within(dimension, radius, at(s), at(t), at(u), false));
  return most;
}

// The pair stiffness k (N/m): K_c times the depth in the plane, times l0 in
// space (a pressure K_c (d - r) / l0 on a particle's face l0^2).
double pair_stiffness(const CaseSpec& spec) {
  return spec.contact.stiffness * (spec.dimension == 3 ? spec.l0 : spec.depth);
}
}  // namespace

void find_contact_candidates(const CaseSpec& spec, const SolverState& s, Range rows,
                             CandidateList& out) {
  if (!spec.contact.enabled) return;
  const ParticleStore& p = s.particles;
  const BondTable& bonds = s.bonds;
  const int interior_bonds =
      lattice_sites_within(p.dimension, bonds.geometry.re / bonds.geometry.l0 * (1.0 - 1e-12));
  // The contacting bodies' ranges met in storage order.
  std::vector<std::pair<Range, std::int32_t>> bodies;
  for (const int b : spec.contact.bodies) {
    const Range r = s.body_ranges[static_cast<std::size_t>(b)];
    const Kind kind = spec.bodies[static_cast<std::size_t>(b)].kind;
    bodies.push_back({r, kind == Kind::wall    ? kWallGroup
                         : kind == Kind::rigid ? static_cast<std::int32_t>(b)
                                               : kNoContactGroup});
  }
  std::sort(bodies.begin(), bodies.end(),
            [](const auto& a, const auto& b) { return a.first.begin < b.first.begin; });
  for (const auto& [r, group] : bodies)
    for (std::size_t i = std::max(r.begin, rows.begin); i < std::min(r.end, rows.end); ++i) {
      int same_body = 0;
      for (std::uint32_t k = bonds.begin(i); k < bonds.end(i); ++k)
        same_body += p.body[bonds.neighbor[k]] == p.body[i];
      if (same_body >= interior_bonds) continue;
      out.index.push_back(static_cast<std::uint32_t>(i));
      out.group.push_back(group);
    }
}

ContactState contact_over(const CaseSpec& spec, const ParticleStore& p, CandidateList candidates) {
  ContactState c;
  c.parameters.distance = spec.contact.distance * spec.l0;
  c.parameters.skin = spec.contact.skin * spec.l0;
  c.parameters.stiffness = pair_stiffness(spec);
  c.parameters.min_distance = spec.contact.min_distance * c.parameters.distance;
  c.candidates = std::move(candidates.index);
  c.group = std::move(candidates.group);
  c.first_moving = static_cast<std::size_t>(
      std::find_if(c.candidates.begin(), c.candidates.end(),
                   [&](std::uint32_t i) { return p.kind[i] != Kind::wall; }) -
      c.candidates.begin());
  c.zero_forces(p.dimension);
  return c;
}

ContactState make_contact(const CaseSpec& spec, const SolverState& s) {
  if (!spec.contact.enabled) return {};
  CandidateList candidates;
  find_contact_candidates(spec, s, s.particles.all(), candidates);
  ContactState c = contact_over(spec, s.particles, std::move(candidates));
  build_contact_list(c, s.particles, s.bonds);
  return c;
}

double contact_omega_squared(const CaseSpec& spec, double largest_inv_mass) {
  if (!spec.contact.enabled) return 0;
  return 2.0 * most_sites_near_a_point(spec.dimension, spec.contact.distance) *
         pair_stiffness(spec) * largest_inv_mass;
}

double largest_contact_inv_mass(const CaseSpec& spec, const std::vector<Range>& body_ranges,
                                const ParticleStore& p, Range held, std::size_t first) {
  if (!spec.contact.enabled) return 0;
  double largest = 0;
  for (const int b : spec.contact.bodies) {
    if (spec.bodies[static_cast<std::size_t>(b)].kind == Kind::wall) continue;
    const Range r = body_ranges[static_cast<std::size_t>(b)];
    for (std::size_t g = std::max(r.begin, held.begin); g < std::min(r.end, held.end); ++g)
      largest = std::max(largest, p.inv_mass[first + (g - held.begin)]);
  }
  return largest;
}

}  // namespace mpsolid
