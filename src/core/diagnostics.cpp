#include "src/core/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/ordered_sum.hpp"

namespace mpsolid {

std::array<double, kMotionSums> motion_terms(const ParticleStore& p, std::size_t i) {
  const double m = 1.0 / p.inv_mass[i];
  const double inertia = 1.0 / p.inv_inertia[i];
  if (p.dimension != 3) {
    const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i];
    return {0.5 * m * v2 + 0.5 * inertia * p.omega[i] * p.omega[i],
            m * p.vx[i],
            m * p.vy[i],
            0.0,
            0.0,
            0.0,
            m * cross(p.x[i], p.y[i], p.vx[i], p.vy[i]) + inertia * p.omega[i],
            p.damping_loss[i]};
  }
  // In space: the momenta as vectors, L = sum m x times v + I w.
  const double vx = p.vx[i], vy = p.vy[i], vz = p.vz[i];
  const double wx = p.omega_x[i], wy = p.omega_y[i], wz = p.omega[i];
  const double x = p.x[i], y = p.y[i], z = p.z[i];
  return {0.5 * m * (vx * vx + vy * vy + vz * vz) + 0.5 * inertia * (wx * wx + wy * wy + wz * wz),
          m * vx,
          m * vy,
          m * vz,
          m * (y * vz - z * vy) + inertia * wx,
          m * (z * vx - x * vz) + inertia * wy,
          m * (x * vy - y * vx) + inertia * wz,
          p.damping_loss[i]};
}

Diagnostics motion_from_sums(const std::array<double, kMotionSums>& sums, double max_speed2) {
  Diagnostics d;
  d.kinetic_energy = sums[0];
  d.momentum_x = sums[1];
  d.momentum_y = sums[2];
  d.momentum_z = sums[3];
  d.angular_momentum_x = sums[4];
  d.angular_momentum_y = sums[5];
  d.angular_momentum = sums[6];
  d.damping_loss = sums[7];
  d.max_speed = std::sqrt(max_speed2);
  return d;
}

Diagnostics motion_diagnostics(const ParticleStore& p) {
  const Range r = p.moving();
  // Each component is summed on its own: the plane's zeros change no other.
  const auto sums =
      ordered_sum<kMotionSums>(r.begin, r.end, [&](std::size_t i) { return motion_terms(p, i); });
  // Max is order-independent: a plain loop is reproducible.
  double vmax2 = 0.0;
  for (std::size_t i = r.begin; i < r.end; ++i) vmax2 = std::max(vmax2, speed_squared(p, i));
  return motion_from_sums(sums, vmax2);
}

std::array<double, 6> extent_of(const ParticleStore& p, Range range) {
  const double inf = std::numeric_limits<double>::infinity();
  std::array<double, 6> extent{inf, -inf, inf, -inf, 0.0, 0.0};
  const std::vector<double>* axes[] = {&p.x, &p.y, &p.z};
  for (int a = 0; a < (p.dimension == 3 ? 3 : 2); ++a) {
    double low = inf, high = -inf;
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double v = (*axes[a])[i];
      if (v < low) low = v;
      if (!(v < high)) high = v;
    }
    extent[2 * a] = low;
    extent[2 * a + 1] = high;
  }
  return extent;
}

void widen(std::array<double, 6>& extent, const std::array<double, 6>& later) {
  for (int a = 0; a < 3; ++a) {
    if (later[2 * a] < extent[2 * a]) extent[2 * a] = later[2 * a];
    if (!(later[2 * a + 1] < extent[2 * a + 1])) extent[2 * a + 1] = later[2 * a + 1];
  }
}

std::array<double, 3> position_of(const ParticleStore& p, std::size_t i) {
  return {p.x[i], p.y[i], p.dimension == 3 ? p.z[i] : 0.0};
}

Diagnostics diagnostics_with_strain_energy(const SolverState& s, double strain_energy) {
  Diagnostics d = motion_diagnostics(s.particles);
  d.strain_energy = strain_energy;
  d.external_work = external_work(s.particles, s.loads);
  for (const RigidBody& body : s.rigid_bodies) d.external_work += body.work;  // drivers
  return d;
}

}  // namespace mpsolid
