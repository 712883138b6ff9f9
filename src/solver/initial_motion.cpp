#include "src/solver/initial_motion.hpp"

#include <cmath>

#include "src/core/loads.hpp"

namespace mpsolid {

double bending_mode_shape(const BendingMode& mode, double x) {
  const double k = mode.kl / mode.length;
  const double m = std::sin(mode.kl) + std::sinh(mode.kl);
  const double n = std::cos(mode.kl) + std::cosh(mode.kl);
  const auto f = [&](double s) {
    return m * (std::cos(k * s) - std::cosh(k * s)) - n * (std::sin(k * s) - std::sinh(k * s));
  };
  return f(x - mode.root_x) / f(mode.length);
}

void apply_initial_motion(SolverState& s, const CaseSpec& spec, bool with_rotation) {
  ParticleStore& p = s.particles;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const BodySpec& body = spec.bodies[b];
    const Range r = s.body_ranges[b];
    if (body.kind == Kind::rigid) {
      for (RigidBody& rb : s.rigid_bodies)
        if (rb.name == body.name) {
          rb.vx = body.velocity[0];
          rb.vy = body.velocity[1];
          rb.omega = body.spin;
          place_rigid_particles(p, rb, with_rotation);
        }
      continue;
    }
    if (body.kind != Kind::elastic) continue;
    double cx = 0, cy = 0;
    centroid(p, r, cx, cy);
    for (std::size_t i = r.begin; i < r.end; ++i) {
      // A spin is a rigid rotation: particles turn with the body.
      p.vx[i] = body.velocity[0] - body.spin * (p.y[i] - cy);
      p.vy[i] = body.velocity[1] + body.spin * (p.x[i] - cx);
      if (with_rotation) p.omega[i] = body.spin;
      if (body.has_mode) p.vy[i] += body.mode.tip_velocity * bending_mode_shape(body.mode, p.x[i]);
      if (body.hold == Hold::x) p.vx[i] = 0.0;
      if (body.hold == Hold::y) p.vy[i] = 0.0;
    }
  }
}

}  // namespace mpsolid
