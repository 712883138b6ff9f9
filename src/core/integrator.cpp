#include "src/core/integrator.hpp"

#include <Eigen/Geometry>

#include "src/core/half_angles.hpp"

namespace mpsolid {

namespace {
// The loops take the arrays as restrict parameters (GCC honours restrict on
// parameters, not on locals): through the store's vectors it cannot rule
// out aliasing and does not vectorise them.
void drift_translation(std::size_t n, double dt, double* __restrict vx, double* __restrict vy,
                       double* __restrict x, double* __restrict y, const double* __restrict fx,
                       const double* __restrict fy, const double* __restrict inv_mass) {
  for (std::size_t i = 0; i < n; ++i) {
    vx[i] += dt * fx[i] * inv_mass[i];
    vy[i] += dt * fy[i] * inv_mass[i];
    x[i] += dt * vx[i];
    y[i] += dt * vy[i];
  }
}

// The third axis in space, with the plane's operations.
void drift_axis(std::size_t n, double dt, double* __restrict v, double* __restrict x,
                const double* __restrict f, const double* __restrict inv_mass) {
  for (std::size_t i = 0; i < n; ++i) {
    v[i] += dt * f[i] * inv_mass[i];
    x[i] += dt * v[i];
  }
}

void drift_rotation(std::size_t n, double dt, double* __restrict omega, double* __restrict theta,
                    double* __restrict half_cos, double* __restrict half_sin,
                    const double* __restrict torque, const double* __restrict inv_inertia) {
  for (std::size_t i = 0; i < n; ++i) {
    omega[i] += dt * torque[i] * inv_inertia[i];
    theta[i] += dt * omega[i];
    const HalfAngle h = half_angle(theta[i]);
    half_cos[i] = h.cos;
    half_sin[i] = h.sin;
  }
}
// In space: omega += dt tau / I (a cubic particle's inertia is isotropic,
// so the spin has no gyroscopic term), then the orientation turned by
// omega dt about the fixed axes and normalised.
void drift_rotation_in_space(ParticleStore& p, Range range, double dt) {
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.omega_x[i] += dt * p.torque_x[i] * p.inv_inertia[i];
    p.omega_y[i] += dt * p.torque_y[i] * p.inv_inertia[i];
    p.omega[i] += dt * p.torque[i] * p.inv_inertia[i];
    const Eigen::Quaterniond q =
        turned(Eigen::Quaterniond(p.qw[i], p.qx[i], p.qy[i], p.qz[i]),
               dt * Eigen::Vector3d(p.omega_x[i], p.omega_y[i], p.omega[i]));
    p.qw[i] = q.w();
    p.qx[i] = q.x();
    p.qy[i] = q.y();
    p.qz[i] = q.z();
  }
}

// In space: the third axis, the spin vector and the quaternion. (Kept apart
// from the plane's loops, which stay as they were.)
void kick_in_space(ParticleStore& p, Range range, double dt, bool with_rotation) {
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.vx[i] += dt * p.fx[i] * p.inv_mass[i];
    p.vy[i] += dt * p.fy[i] * p.inv_mass[i];
    p.vz[i] += dt * p.fz[i] * p.inv_mass[i];
    if (!with_rotation) continue;
    p.omega_x[i] += dt * p.torque_x[i] * p.inv_inertia[i];
    p.omega_y[i] += dt * p.torque_y[i] * p.inv_inertia[i];
    p.omega[i] += dt * p.torque[i] * p.inv_inertia[i];
  }
}
void kick_drift_in_space(ParticleStore& p, Range range, double dt, bool with_rotation) {
  const std::size_t b = range.begin, n = range.end > b ? range.end - b : 0;
  drift_translation(n, dt, &p.vx[b], &p.vy[b], &p.x[b], &p.y[b], &p.fx[b], &p.fy[b],
                    &p.inv_mass[b]);
  drift_axis(n, dt, &p.vz[b], &p.z[b], &p.fz[b], &p.inv_mass[b]);
  if (with_rotation) drift_rotation_in_space(p, range, dt);
}
}  // namespace

void kick_drift(ParticleStore& p, Range range, double dt, bool with_rotation) {
  if (p.dimension == 3) return kick_drift_in_space(p, range, dt, with_rotation);
  const std::size_t b = range.begin, n = range.end > b ? range.end - b : 0;
  drift_translation(n, dt, &p.vx[b], &p.vy[b], &p.x[b], &p.y[b], &p.fx[b], &p.fy[b],
                    &p.inv_mass[b]);
  if (with_rotation)
    drift_rotation(n, dt, &p.omega[b], &p.theta[b], &p.half_cos[b], &p.half_sin[b], &p.torque[b],
                   &p.inv_inertia[b]);
}

void kick(ParticleStore& p, Range range, double dt, bool with_rotation) {
  if (p.dimension == 3) return kick_in_space(p, range, dt, with_rotation);
  for (std::size_t i = range.begin; i < range.end; ++i) {
    p.vx[i] += dt * p.fx[i] * p.inv_mass[i];
    p.vy[i] += dt * p.fy[i] * p.inv_mass[i];
    if (with_rotation) p.omega[i] += dt * p.torque[i] * p.inv_inertia[i];
  }
}

}  // namespace mpsolid
