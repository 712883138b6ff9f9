#include "src/core/diagnostics.hpp"

#include <algorithm>
#include <cmath>

#include "src/core/ordered_sum.hpp"

namespace mpsolid {

Diagnostics motion_diagnostics(const ParticleStore& p) {
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
  double vmax2 = 0.0;  // max is order-independent: a plain loop is reproducible
  for (std::size_t i = r.begin; i < r.end; ++i)
    vmax2 = std::max(vmax2, p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i]);
  d.max_speed = std::sqrt(vmax2);
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
