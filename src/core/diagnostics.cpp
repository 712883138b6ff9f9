#include "src/core/diagnostics.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/ordered_sum.hpp"

namespace mpsolid {

namespace {
// Max is order-independent: a plain loop is reproducible.
double max_speed(const ParticleStore& p, Range r) {
  double vmax2 = 0.0;
  for (std::size_t i = r.begin; i < r.end; ++i) vmax2 = std::max(vmax2, speed_squared(p, i));
  return std::sqrt(vmax2);
}

// In space: the momenta as vectors, L = sum m x times v + I w.
Diagnostics motion_diagnostics_in_space(const ParticleStore& p) {
  const Range r = p.moving();
  const auto sums = ordered_sum<8>(r.begin, r.end, [&](std::size_t i) {
    const double m = 1.0 / p.inv_mass[i];
    const double inertia = 1.0 / p.inv_inertia[i];
    const double vx = p.vx[i], vy = p.vy[i], vz = p.vz[i];
    const double wx = p.omega_x[i], wy = p.omega_y[i], wz = p.omega[i];
    const double x = p.x[i], y = p.y[i], z = p.z[i];
    return std::array<double, 8>{
        0.5 * m * (vx * vx + vy * vy + vz * vz) + 0.5 * inertia * (wx * wx + wy * wy + wz * wz),
        m * vx,
        m * vy,
        m * vz,
        m * (y * vz - z * vy) + inertia * wx,
        m * (z * vx - x * vz) + inertia * wy,
        m * (x * vy - y * vx) + inertia * wz,
        p.damping_loss[i]};
  });
  Diagnostics d;
  d.kinetic_energy = sums[0];
  d.momentum_x = sums[1];
  d.momentum_y = sums[2];
  d.momentum_z = sums[3];
  d.angular_momentum_x = sums[4];
  d.angular_momentum_y = sums[5];
  d.angular_momentum = sums[6];
  d.damping_loss = sums[7];
  d.max_speed = max_speed(p, r);
  return d;
}
}  // namespace

Diagnostics motion_diagnostics(const ParticleStore& p) {
  if (p.dimension == 3) return motion_diagnostics_in_space(p);
  const Range r = p.moving();
  const auto sums = ordered_sum<5>(r.begin, r.end, [&](std::size_t i) {
    const double m = 1.0 / p.inv_mass[i];
    const double inertia = 1.0 / p.inv_inertia[i];
    const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i];
    return std::array<double, 5>{
        0.5 * m * v2 + 0.5 * inertia * p.omega[i] * p.omega[i], m * p.vx[i], m * p.vy[i],
        m * cross(p.x[i], p.y[i], p.vx[i], p.vy[i]) + inertia * p.omega[i], p.damping_loss[i]};
  });
  Diagnostics d;
  d.kinetic_energy = sums[0];
  d.momentum_x = sums[1];
  d.momentum_y = sums[2];
  d.angular_momentum = sums[3];
  d.damping_loss = sums[4];
  d.max_speed = max_speed(p, r);
  return d;
}

Diagnostics diagnostics_with_strain_energy(const SolverState& s, double strain_energy) {
  Diagnostics d = motion_diagnostics(s.particles);
  d.strain_energy = strain_energy;
  d.external_work = external_work(s.particles, s.loads);
  for (const RigidBody& body : s.rigid_bodies) d.external_work += body.work;  // drivers
  return d;
}

}  // namespace mpsolid
