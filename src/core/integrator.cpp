#include "src/core/integrator.hpp"

#include "src/core/half_angles.hpp"

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
    set_half_angle(p, i);
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
