#include "src/solver/initial_motion.hpp"

#include <array>
#include <cmath>
#include <tuple>

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

namespace {
// An elastic body's motion in space: v = v0 + w x (x - c), every particle
// turning at w with the body, plus the bending mode, less the held component.
void apply_motion_in_space(ParticleStore& p, const BodySpec& body, Range r,
                           const std::array<double, 3>& c, bool with_rotation) {
  const double* w = body.spin;
  for (std::size_t i = r.begin; i < r.end; ++i) {
    const double dx = p.x[i] - c[0], dy = p.y[i] - c[1], dz = p.z[i] - c[2];
    p.vx[i] = body.velocity[0] + (w[1] * dz - w[2] * dy);
    p.vy[i] = body.velocity[1] + (w[2] * dx - w[0] * dz);
    p.vz[i] = body.velocity[2] + (w[0] * dy - w[1] * dx);
    if (with_rotation) {
      p.omega_x[i] = w[0];
      p.omega_y[i] = w[1];
      p.omega[i] = w[2];
    }
    if (body.has_mode) p.vy[i] += body.mode.tip_velocity * bending_mode_shape(body.mode, p.x[i]);
    if (body.hold == Hold::x) p.vx[i] = 0.0;
    if (body.hold == Hold::y) p.vy[i] = 0.0;
    if (body.hold == Hold::z) p.vz[i] = 0.0;
  }
}
}  // namespace

void apply_initial_motion(SolverState& s, const CaseSpec& spec, bool with_rotation,
                          const std::vector<std::array<double, 3>>* centroids) {
  ParticleStore& p = s.particles;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const BodySpec& body = spec.bodies[b];
    const Range r = s.body_ranges[b];
    if (body.kind == Kind::rigid) {
      for (RigidBody& rb : s.rigid_bodies)
        if (rb.name == body.name) {
          set_rigid_motion(p, rb, body.velocity, body.spin, with_rotation);
        }
      continue;
    }
    if (body.kind != Kind::elastic) continue;
    double cx = 0, cy = 0, cz = 0;
    if (centroids)
      std::tie(cx, cy, cz) = std::tuple((*centroids)[b][0], (*centroids)[b][1], (*centroids)[b][2]);
    else
      centroid(p, r, cx, cy, cz);
    if (p.dimension == 3) {
      apply_motion_in_space(p, body, r, {cx, cy, cz}, with_rotation);
      continue;
    }
    for (std::size_t i = r.begin; i < r.end; ++i) {
      // A spin is a rigid rotation: particles turn with the body.
      p.vx[i] = body.velocity[0] - body.spin[2] * (p.y[i] - cy);
      p.vy[i] = body.velocity[1] + body.spin[2] * (p.x[i] - cx);
      if (with_rotation) p.omega[i] = body.spin[2];
      if (body.has_mode) p.vy[i] += body.mode.tip_velocity * bending_mode_shape(body.mode, p.x[i]);
      if (body.hold == Hold::x) p.vx[i] = 0.0;
      if (body.hold == Hold::y) p.vy[i] = 0.0;
    }
  }
}

}  // namespace mpsolid
