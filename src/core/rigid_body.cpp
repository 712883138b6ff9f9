#include "src/core/rigid_body.hpp"

#include <cmath>

#include "src/core/half_angles.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid {

RigidBody make_rigid_body(const ParticleStore& p, std::string name, Range range) {
  RigidBody body;
  body.name = std::move(name);
  body.range = range;
  const auto n = static_cast<double>(range.size());
  const auto [sx, sy] = ordered_sum<2>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 2>{p.x0[i], p.y0[i]};
  });
  body.xg0 = body.xg = sx / n;
  body.yg0 = body.yg = sy / n;
  body.dx0.resize(range.size());
  body.dy0.resize(range.size());
  double orbital = 0.0, spin = 0.0, mass = 0.0;
  for (std::size_t k = 0; k < range.size(); ++k) {
    const std::size_t i = range.begin + k;
    body.dx0[k] = p.x0[i] - body.xg0;
    body.dy0[k] = p.y0[i] - body.yg0;
    const double m = 1.0 / p.inv_mass[i];
    mass += m;
    orbital += m * (body.dx0[k] * body.dx0[k] + body.dy0[k] * body.dy0[k]);
    spin += 1.0 / p.inv_inertia[i];
  }
  body.mass_total = mass;
  body.orbital_inertia = orbital;
  body.spin_inertia = spin;
  return body;
}

void project_rigid_body(ParticleStore& p, RigidBody& body, double t, double dt,
                        bool with_rotation) {
  const Range r = body.range;
  // Linear momentum and angular momentum about the centroid (orbital + spin).
  const auto [px, py, lz] = ordered_sum<3>(r.begin, r.end, [&](std::size_t i) {
    const double m = 1.0 / p.inv_mass[i];
    const double spin = with_rotation ? p.omega[i] / p.inv_inertia[i] : 0.0;
    return std::array<double, 3>{
        m * p.vx[i], m * p.vy[i],
        m * cross(p.x[i] - body.xg, p.y[i] - body.yg, p.vx[i], p.vy[i]) + spin};
  });
  // Without particle spins (models without rotation) only the orbital part counts.
  const double inertia = body.orbital_inertia + (with_rotation ? body.spin_inertia : 0.0);
  if (body.motion.on) {
    const PrescribedMotion& m = body.motion;
    const double f = m.factor(t, dt);
    const double vx = f * m.vx, vy = f * m.vy, omega = f * m.spin;
    // The driver's impulse beyond the forces, times the step's mean velocity
    // (a sudden start costs the body's kinetic energy, not twice it).
    body.work += (body.mass_total * vx - px) * 0.5 * (body.vx + vx) +
                 (body.mass_total * vy - py) * 0.5 * (body.vy + vy) +
                 (inertia * omega - lz) * 0.5 * (body.omega + omega);
    body.vx = vx;
    body.vy = vy;
    body.omega = omega;
  } else {
    body.vx = px / body.mass_total;
    body.vy = py / body.mass_total;
    body.omega = lz / inertia;
  }
  body.xg += dt * body.vx;
  body.yg += dt * body.vy;
  body.angle += dt * body.omega;
  place_rigid_particles(p, body, with_rotation);
}

void place_rigid_particles(ParticleStore& p, const RigidBody& body, bool with_rotation) {
  const double c = std::cos(body.angle), s = std::sin(body.angle);
  const HalfAngle half = half_angle(body.angle);  // theta = Theta for every particle
  parallel_for(body.range.begin, body.range.end, [&](std::size_t i) {
    const std::size_t k = i - body.range.begin;
    const double dx = c * body.dx0[k] - s * body.dy0[k];
    const double dy = s * body.dx0[k] + c * body.dy0[k];
    p.x[i] = body.xg + dx;
    p.y[i] = body.yg + dy;
    p.vx[i] = body.vx - body.omega * dy;
    p.vy[i] = body.vy + body.omega * dx;
    if (with_rotation) {
      p.theta[i] = body.angle;
      p.omega[i] = body.omega;
      p.half_cos[i] = half.cos;
      p.half_sin[i] = half.sin;
    }
  });
}

}  // namespace mpsolid
