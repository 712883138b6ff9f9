#include "src/solver/contact_setup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "neighbor/contact_search.hpp"

namespace mpsolid {

namespace {
// Walls never move: all of them share one group.
constexpr std::int32_t kWallGroup = -2;

// Lattice offsets (a, b) != 0 with |(a, b)| < radius: the bonds of an
// interior particle when radius = re / l0.
int lattice_sites_within(double radius, double u = 0, double v = 0, bool skip_origin = true) {
  const int reach = static_cast<int>(std::ceil(radius)) + 1;
  int count = 0;
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b) {
      if (skip_origin && a == 0 && b == 0) continue;
      const double dx = a - u, dy = b - v;
      if (dx * dx + dy * dy < radius * radius) ++count;
    }
  return count;
}

// The most lattice sites (spacing 1) closer than `radius` to any point.
int most_sites_near_a_point(double radius) {
  constexpr int kSamples = 40;
  int most = 0;
  for (int s = 0; s <= kSamples; ++s)
    for (int t = 0; t <= s; ++t)  // the cell's symmetric eighth suffices
      most = std::max(most,
                      lattice_sites_within(radius, 0.5 * s / kSamples, 0.5 * t / kSamples, false));
  return most;
}
}  // namespace

ContactState make_contact(const CaseSpec& spec, const SolverState& s) {
  ContactState c;
  if (!spec.contact.enabled) return c;
  const ParticleStore& p = s.particles;
  const BondTable& bonds = s.bonds;
  c.parameters.distance = spec.contact.distance * spec.l0;
  c.parameters.skin = spec.contact.skin * spec.l0;
  c.parameters.stiffness = spec.contact.stiffness * spec.depth;
  c.parameters.min_distance = spec.contact.min_distance * c.parameters.distance;
  const int interior_bonds =
      lattice_sites_within(bonds.geometry.re / bonds.geometry.l0 * (1.0 - 1e-12));
  std::vector<bool> contacting(p.size(), false);
  std::vector<std::int32_t> group_of(p.size(), kNoContactGroup);
  for (const int b : spec.contact.bodies) {
    const Range r = s.body_ranges[static_cast<std::size_t>(b)];
    const Kind kind = spec.bodies[static_cast<std::size_t>(b)].kind;
    for (std::size_t i = r.begin; i < r.end; ++i) {
      contacting[i] = true;
      group_of[i] = kind == Kind::wall ? kWallGroup : kind == Kind::rigid ? b : kNoContactGroup;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!contacting[i]) continue;
    int same_body = 0;
    for (std::uint32_t k = bonds.begin(i); k < bonds.end(i); ++k)
      same_body += p.body[bonds.neighbor[k]] == p.body[i];
    if (same_body >= interior_bonds) continue;
    c.candidates.push_back(static_cast<std::uint32_t>(i));
    c.group.push_back(group_of[i]);
  }
  c.first_moving = static_cast<std::size_t>(
      std::find_if(c.candidates.begin(), c.candidates.end(),
                   [&](std::uint32_t i) { return p.kind[i] != Kind::wall; }) -
      c.candidates.begin());
  c.force_x.assign(c.size(), 0.0);
  c.force_y.assign(c.size(), 0.0);
  build_contact_list(c, p, bonds);
  return c;
}

double contact_omega_squared(const CaseSpec& spec, const SolverState& s) {
  if (!spec.contact.enabled) return 0;
  const ParticleStore& p = s.particles;
  double largest_inv_mass = 0;
  for (const int b : spec.contact.bodies) {
    const Range r = s.body_ranges[static_cast<std::size_t>(b)];
    if (spec.bodies[static_cast<std::size_t>(b)].kind == Kind::wall) continue;
    for (std::size_t i = r.begin; i < r.end; ++i)
      largest_inv_mass = std::max(largest_inv_mass, p.inv_mass[i]);
  }
  const double k = spec.contact.stiffness * spec.depth;
  return 2.0 * most_sites_near_a_point(spec.contact.distance) * k * largest_inv_mass;
}

}  // namespace mpsolid
