#include "src/core/damping.hpp"

namespace mpsolid {

void damp_block(ParticleStore& p, Range range, double coefficient, double dt, bool with_rotation) {
  const double beta = 1.0 + 0.5 * coefficient * dt;
  const bool space = p.dimension == 3;
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
    // One more component of force and velocity (z, a spin's x or y in
    // space), as above: damped, and its loss counted.
    const auto damp = [&](double& f, double v, double inverse) {
      const double damped = (f - coefficient * v / inverse) / beta;
      loss -= dt * (damped - f) * (v + 0.5 * dt * damped * inverse);
      f = damped;
    };
    if (space) damp(p.fz[i], p.vz[i], p.inv_mass[i]);
    if (with_rotation) {
      const double inertia = 1.0 / p.inv_inertia[i];
      const double torque = (p.torque[i] - coefficient * inertia * p.omega[i]) / beta;
      const double omega = p.omega[i] + 0.5 * dt * torque * p.inv_inertia[i];
      loss -= dt * (torque - p.torque[i]) * omega;
      p.torque[i] = torque;
      if (space) {
        damp(p.torque_x[i], p.omega_x[i], p.inv_inertia[i]);
        damp(p.torque_y[i], p.omega_y[i], p.inv_inertia[i]);
      }
    }
    p.damping_loss[i] += loss;
  }
}

}  // namespace mpsolid
