#pragma once
// The contact force pass (MODEL.md section 8): a frictionless repulsion
// between candidates closer than the contact distance d, from the potential
// U(r) = k/2 (d - r)^2 (zero, with zero force, at r = d). Each candidate
// gathers its own pairs in ascending partner order, so the force on j from i
// is the force on i from j negated bit for bit and any thread count gives
// the same bits. A pair at or beyond d adds nothing (not even +0.0), so the
// sums do not depend on which farther pairs the Verlet list holds.
#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include "src/core/contact_state.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/stability.hpp"

namespace mpsolid {

// Calls pair(j, dx, dy, dz, r) for each partner j of candidate a closer
// than d, in ascending j, with (dx, dy, dz) = r_i - r_j (dz = 0 in the
// plane).
template <class Pair>
inline void for_each_touching(const ContactState& c, const ParticleStore& p, std::size_t a,
                              Pair&& pair) {
  const std::size_t i = c.candidates[a];
  const double d2 = c.parameters.distance * c.parameters.distance;
  const bool space = p.dimension == 3;
  for (std::uint32_t k = c.offsets[a]; k < c.offsets[a + 1]; ++k) {
    const std::size_t j = c.partner[k];
    const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
    const double dz = space ? p.z[i] - p.z[j] : 0.0;
    double r2 = dx * dx + dy * dy;
    if (space) r2 += dz * dz;
    if (r2 < d2) pair(j, dx, dy, dz, std::sqrt(r2));
  }
}

// The contact forces of candidates [range.begin, range.end) in step
// `step`; marks the list stale in that step (and leaves the forces to be
// recomputed) when it is not valid for one of them.
inline void compute_contact_forces(ContactState& c, const ParticleStore& p, Range range,
                                   std::int64_t step) {
  const double k = c.parameters.stiffness, d = c.parameters.distance;
  for (std::size_t a = range.begin; a < range.end; ++a) {
    if (c.moved_past_half_skin(p, a)) {
      c.stale.step.store(step, std::memory_order_relaxed);
      return;
    }
    double fx = 0, fy = 0, fz = 0;
    for_each_touching(c, p, a, [&](std::size_t, double dx, double dy, double dz, double r) {
      if (r < c.parameters.min_distance) {
        std::int64_t none = -1;  // keeps the first step: steps only grow
        c.too_close.step.compare_exchange_strong(none, step, std::memory_order_relaxed);
      }
      const double push = k * (d - r) / r;
      fx += push * dx;
      fy += push * dy;
      fz += push * dz;
    });
    c.force_x[a] = fx;
    c.force_y[a] = fy;
    if (!c.force_z.empty()) c.force_z[a] = fz;
  }
}

// Adds the contact forces of the candidates stored in `block` to fx, fy.
inline void add_contact_forces(ParticleStore& p, const ContactState& c, Range block) {
  const bool space = !c.force_z.empty();
  c.for_candidates_in(block, [&](std::size_t a) {
    p.fx[c.candidates[a]] += c.force_x[a];
    p.fy[c.candidates[a]] += c.force_y[a];
    if (space) p.fz[c.candidates[a]] += c.force_z[a];
  });
}

// Candidate a's share of the contact energy: half of each of its pairs'.
inline double contact_energy_share(const ContactState& c, const ParticleStore& p, std::size_t a) {
  const double k = c.parameters.stiffness, d = c.parameters.distance;
  double e = 0;
  for_each_touching(c, p, a, [&](std::size_t, double, double, double, double r) {
    e += 0.25 * k * (d - r) * (d - r);
  });
  return e;
}

// The interpenetration check: a pair closer than min_distance now, or in a
// step since the last check (the contact pass marks the first such step).
// Names the closest touching pair now (the list must be valid); when none
// touches any more, has_neighbor is false and the caller names the pair.
inline StabilityVerdict check_interpenetration(const ContactState& c, const ParticleStore& p) {
  StabilityVerdict v;
  v.value = std::numeric_limits<double>::infinity();
  for (std::size_t a = c.first_moving; a < c.size(); ++a)
    for_each_touching(c, p, a, [&](std::size_t j, double, double, double, double r) {
      if (r < v.value) {
        v.value = r;
        v.particle = c.candidates[a];
        v.neighbor = j;
        v.has_neighbor = true;
      }
    });
  v.limit = c.parameters.min_distance;
  const std::int64_t when = c.too_close.step.load(std::memory_order_relaxed);
  if (!(v.value < v.limit) && when < 0) return v;
  v.ok = false;
  v.neighbor_role = "too close to (not bonded)";
  const std::string limit =
      fmt::format("closer than {:g} of the contact distance {:.4g} m (contact.min_distance)",
                  v.limit / c.parameters.distance, c.parameters.distance);
  const char* advice =
      "the contact is too soft for this impact (raise contact.stiffness) or the step too large";
  if (v.value < v.limit)
    v.criterion = fmt::format(
        "interpenetration: two particles that are not bonded are {:.4g} m apart, {}; {}", v.value,
        limit, advice);
  else
    v.criterion =
        fmt::format("interpenetration: two particles that are not bonded came {} at step {}; {}",
                    limit, when, advice);
  return v;
}

}  // namespace mpsolid
