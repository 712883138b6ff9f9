#include "src/core/damping.hpp"

namespace mpsolid {

void damp_block(ParticleStore& p, Range range, double coefficient, double dt, bool with_rotation) {
  const double beta = 1.0 + 0.5 * coefficient * dt;
  for (std::size_t i = range.begin; i < range.end; ++i) {
    const double m = 1.0 / p.inv_mass[i];
    const double fx = (p.fx[i] - coefficient * m * p.vx[i]) / beta;
    const double fy = (p.fy[i] - coefficient * m * p.vy[i]) / beta;
    // The damping force's work over the step, at the mean velocity.
    const double vx = p.vx[i] + 0.5 * dt * fx * p.inv_mass[i];
    const double vy = p.vy[i] + 0.5 * dt * fy * p.inv_mass[i];
    double loss = -dt * ((fx - p.fx[i]) * vx + (fy - p.fy[i]) * vy);
    p.fx[i] = fx;
    p.fy[i] = fy;
    if (with_rotation) {
      const double inertia = 1.0 / p.inv_inertia[i];
      const double torque = (p.torque[i] - coefficient * inertia * p.omega[i]) / beta;
      const double omega = p.omega[i] + 0.5 * dt * torque * p.inv_inertia[i];
      loss -= dt * (torque - p.torque[i]) * omega;
      p.torque[i] = torque;
    }
    p.damping_loss[i] += loss;
  }
}

}  // namespace mpsolid
