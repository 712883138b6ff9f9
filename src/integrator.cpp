#include "src/integrator.hpp"

#include <cmath>

namespace mpsolid {

void kick_drift(ParticleStore& p, Range range, double dt, bool with_rotation) {
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.vx[i] += dt * p.fx[i] * p.inv_mass[i];
    p.vy[i] += dt * p.fy[i] * p.inv_mass[i];
    p.x[i] += dt * p.vx[i];
    p.y[i] += dt * p.vy[i];
  }
  if (!with_rotation) return;
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.omega[i] += dt * p.torque[i] * p.inv_inertia[i];
    p.theta[i] += dt * p.omega[i];
    // The same expressions as compute_half_angles: the same bits.
    p.half_cos[i] = std::cos(0.5 * p.theta[i]);
    p.half_sin[i] = std::sin(0.5 * p.theta[i]);
  }
}

void kick(ParticleStore& p, Range range, double dt, bool with_rotation) {
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.vx[i] += dt * p.fx[i] * p.inv_mass[i];
    p.vy[i] += dt * p.fy[i] * p.inv_mass[i];
    if (with_rotation) p.omega[i] += dt * p.torque[i] * p.inv_inertia[i];
  }
}

}  // namespace mpsolid
