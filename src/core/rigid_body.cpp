#include "src/core/rigid_body.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "src/core/half_angles.hpp"
#include "src/core/integrator.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/core/parallel.hpp"
#include "src/core/rigid_rotation3.hpp"

namespace mpsolid {

namespace {
// The pose's fields in pose_values' order, as pointers into `b`.
template <class Body>
auto pose_fields(Body& b) {
  using Field = std::conditional_t<std::is_const_v<Body>, const double*, double*>;
  if (b.dimension == 3)
    return std::vector<Field>{&b.xg,
                              &b.yg,
                              &b.zg,
                              &b.frame[0],
                              &b.frame[1],
                              &b.frame[2],
                              &b.frame[3],
                              &b.vx,
                              &b.vy,
                              &b.vz,
                              &b.omega_x,
                              &b.omega_y,
                              &b.omega,
                              &b.angular_momentum[0],
                              &b.angular_momentum[1],
                              &b.angular_momentum[2]};
  return std::vector<Field>{&b.xg, &b.yg, &b.angle, &b.vx, &b.vy, &b.omega};
}

Eigen::Quaterniond quaternion(const std::array<double, 4>& q) {
  return {q[0], q[1], q[2], q[3]};
}
std::array<double, 4> components(const Eigen::Quaterniond& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}
Eigen::Vector3d as_vector(const std::array<double, 3>& v) {
  return {v[0], v[1], v[2]};
}

// The principal moments in effect: the particles' own spins count only
// where the model gives them spins.
Eigen::Vector3d moments_of(const RigidBody& b, bool with_rotation) {
  const Eigen::Vector3d orbital = as_vector(b.orbital_moments);
  return with_rotation ? Eigen::Vector3d(orbital.array() + b.spin_inertia) : orbital;
}

// A body's angular velocity in the body frame from its momentum there, 0
// about an axis of no inertia (a line of particles about its own axis, which
// no momentum can turn).
Eigen::Vector3d body_rate(const Eigen::Vector3d& momentum, const Eigen::Vector3d& moments) {
  Eigen::Vector3d w;
  for (int a = 0; a < 3; ++a) w[a] = moments[a] > 0 ? momentum[a] / moments[a] : 0.0;
  return w;
}

void make_in_space(const ParticleStore& p, RigidBody& body) {
  const Range range = body.range;
  const auto n = static_cast<double>(range.size());
  const auto [sx, sy, sz] = ordered_sum<3>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 3>{p.x0[i], p.y0[i], p.z0[i]};
  });
  body.xg0 = body.xg = sx / n;
  body.yg0 = body.yg = sy / n;
  body.zg0 = body.zg = sz / n;
  const auto count = static_cast<Eigen::Index>(range.size());
  Eigen::Matrix3Xd offsets(3, count);
  Eigen::VectorXd masses(count);
  body.dx0.resize(range.size());
  body.dy0.resize(range.size());
  body.dz0.resize(range.size());
  double spin = 0.0, mass = 0.0;
  for (std::size_t k = 0; k < range.size(); ++k) {
    const std::size_t i = range.begin + k;
    body.dx0[k] = p.x0[i] - body.xg0;
    body.dy0[k] = p.y0[i] - body.yg0;
    body.dz0[k] = p.z0[i] - body.zg0;
    offsets.col(static_cast<Eigen::Index>(k)) << body.dx0[k], body.dy0[k], body.dz0[k];
    masses[static_cast<Eigen::Index>(k)] = 1.0 / p.inv_mass[i];
    mass += masses[static_cast<Eigen::Index>(k)];
    spin += 1.0 / p.inv_inertia[i];
  }
  const PrincipalAxes principal = principal_axes(
      inertia_tensor(offsets, masses, Eigen::Vector3d::Zero(), Eigen::VectorXd::Zero(count)));
  for (int a = 0; a < 3; ++a) body.orbital_moments[a] = std::max(principal.moments[a], 0.0);
  body.axes = components(Eigen::Quaterniond(principal.axes).normalized());
  body.frame = body.axes;
  body.mass_total = mass;
  body.spin_inertia = spin;
}

// The rigid field at a particle d from the centroid, as placed: position and
// velocity. The projection recomputes it with the same operations, so a
// particle no force touched differs from it by exactly nothing.
struct Placed {
  Eigen::Vector3d d, v;
};
Placed placed(const RigidBody& b, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& w,
              std::size_t k) {
  const Eigen::Vector3d d = rotation * Eigen::Vector3d(b.dx0[k], b.dy0[k], b.dz0[k]);
  return {d, Eigen::Vector3d(b.vx, b.vy, b.vz) + w.cross(d)};
}

Eigen::Matrix3d rotation_matrix(const RigidBody& b) {
  return quaternion(rotation_from_start(b)).toRotationMatrix();
}

// L = I w with the body's inertia tensor in its current frame.
Eigen::Vector3d momentum_of(const Eigen::Quaterniond& frame, const Eigen::Vector3d& moments,
                            const Eigen::Vector3d& w) {
  return frame * moments.cwiseProduct(frame.conjugate() * w);
}

// In space: the impulse the step gave the body, its particles' momenta less
// those of the rigid field they were placed with (spins included).
std::array<double, kProjectionSums> impulse_term(const ParticleStore& p, const RigidBody& body,
                                                 const Eigen::Matrix3d& rotation,
                                                 const Eigen::Vector3d& w_old, std::size_t i,
                                                 bool with_rotation) {
  const Placed at = placed(body, rotation, w_old, i - body.range.begin);
  const double m = 1.0 / p.inv_mass[i];
  const Eigen::Vector3d dv = Eigen::Vector3d(p.vx[i], p.vy[i], p.vz[i]) - at.v;
  Eigen::Vector3d dl = m * at.d.cross(dv);
  if (with_rotation)
    dl += (Eigen::Vector3d(p.omega_x[i], p.omega_y[i], p.omega[i]) - w_old) / p.inv_inertia[i];
  return {m * dv[0], m * dv[1], m * dv[2], dl[0], dl[1], dl[2]};
}

void advance_in_space(ParticleStore& p, RigidBody& body,
                      const std::array<double, kProjectionSums>& impulse, double t, double dt,
                      bool with_rotation) {
  const Eigen::Vector3d v_old(body.vx, body.vy, body.vz);
  const Eigen::Vector3d w_old(body.omega_x, body.omega_y, body.omega);
  const Eigen::Vector3d momentum =
      body.mass_total * v_old + Eigen::Vector3d(impulse[0], impulse[1], impulse[2]);
  const Eigen::Vector3d angular =
      as_vector(body.angular_momentum) + Eigen::Vector3d(impulse[3], impulse[4], impulse[5]);
  const Eigen::Vector3d moments = moments_of(body, with_rotation);
  Eigen::Quaterniond frame = quaternion(body.frame);
  Eigen::Vector3d v, w, l = angular;
  if (body.motion.on) {
    const PrescribedMotion& m = body.motion;
    const double f = m.factor(t, dt);
    v = f * as_vector(m.velocity);
    w = f * as_vector(m.spin);
    // The driver's impulse beyond the forces, times the step's mean velocity;
    // the angular one with the body's inertia tensor now.
    body.work += (body.mass_total * v - momentum).dot(0.5 * (v_old + v)) +
                 (momentum_of(frame, moments, w) - angular).dot(0.5 * (w_old + w));
    frame = turned(frame, dt * w);
    l = momentum_of(frame, moments, w);
  } else {
    v = momentum / body.mass_total;
    Eigen::Vector3d in_body = frame.conjugate() * angular;
    rotate_free(frame, in_body, moments, dt);
    w = frame * body_rate(in_body, moments);
  }
  body.frame = components(frame);
  body.angular_momentum = {l[0], l[1], l[2]};
  body.vx = v[0];
  body.vy = v[1];
  body.vz = v[2];
  body.omega_x = w[0];
  body.omega_y = w[1];
  body.omega = w[2];
  body.xg += dt * body.vx;
  body.yg += dt * body.vy;
  body.zg += dt * body.vz;
  place_rigid_particles(p, body, with_rotation);
}

void place_in_space(ParticleStore& p, const RigidBody& body, bool with_rotation) {
  const Eigen::Quaterniond turn = quaternion(rotation_from_start(body));
  const Eigen::Matrix3d rotation = turn.toRotationMatrix();
  const Eigen::Vector3d w(body.omega_x, body.omega_y, body.omega);
  parallel_for(body.range.begin, body.range.end, [&](std::size_t i) {
    const Placed at = placed(body, rotation, w, i - body.range.begin);
    p.x[i] = body.xg + at.d[0];
    p.y[i] = body.yg + at.d[1];
    p.z[i] = body.zg + at.d[2];
    p.vx[i] = at.v[0];
    p.vy[i] = at.v[1];
    p.vz[i] = at.v[2];
    if (with_rotation) {
      p.qw[i] = turn.w();
      p.qx[i] = turn.x();
      p.qy[i] = turn.y();
      p.qz[i] = turn.z();
      p.omega_x[i] = w[0];
      p.omega_y[i] = w[1];
      p.omega[i] = w[2];
    }
  });
}
}  // namespace

std::size_t pose_size(int dimension) {
  return dimension == 3 ? 16 : 6;
}

std::vector<double> pose_values(const RigidBody& body) {
  std::vector<double> out;
  for (const double* v : pose_fields(body)) out.push_back(*v);
  return out;
}

void set_pose_values(RigidBody& body, const double* values) {
  for (double* v : pose_fields(body)) *v = *values++;
}

std::array<double, 4> rotation_from_start(const RigidBody& body) {
  return components((quaternion(body.frame) * quaternion(body.axes).conjugate()).normalized());
}

void set_rigid_motion(ParticleStore& p, RigidBody& body, const double velocity[3],
                      const double spin[3], bool with_rotation) {
  body.vx = velocity[0];
  body.vy = velocity[1];
  body.omega = spin[2];
  if (body.dimension == 3) {
    body.vz = velocity[2];
    body.omega_x = spin[0];
    body.omega_y = spin[1];
    const Eigen::Vector3d l = momentum_of(quaternion(body.frame), moments_of(body, with_rotation),
                                          Eigen::Vector3d(spin[0], spin[1], spin[2]));
    body.angular_momentum = {l[0], l[1], l[2]};
  }
  place_rigid_particles(p, body, with_rotation);
}

RigidBody make_rigid_body(const ParticleStore& p, std::string name, Range range) {
  RigidBody body;
  body.name = std::move(name);
  body.range = range;
  body.dimension = p.dimension;
  if (p.dimension == 3) {
    make_in_space(p, body);
    return body;
  }
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

ProjectionTerms::ProjectionTerms(const ParticleStore& p, const RigidBody& body, bool with_rotation)
    : p_(p), body_(body), with_rotation_(with_rotation) {
  if (body.dimension != 3) return;
  rotation_ = rotation_matrix(body);
  w_old_ = {body.omega_x, body.omega_y, body.omega};
}

std::array<double, kProjectionSums> ProjectionTerms::operator()(std::size_t i) const {
  const ParticleStore& p = p_;
  const RigidBody& body = body_;
  if (body.dimension == 3)
    return impulse_term(p, body, rotation_, Eigen::Vector3d(w_old_[0], w_old_[1], w_old_[2]), i,
                        with_rotation_);
  // Linear momentum and angular momentum about the centroid (orbital + spin).
  const double m = 1.0 / p.inv_mass[i];
  const double spin = with_rotation_ ? p.omega[i] / p.inv_inertia[i] : 0.0;
  return {m * p.vx[i],
          m * p.vy[i],
          m * cross(p.x[i] - body.xg, p.y[i] - body.yg, p.vx[i], p.vy[i]) + spin,
          0.0,
          0.0,
          0.0};
}

RigidBody rigid_body_part(const RigidBody& whole, Range range,
                          const std::vector<std::size_t>& places) {
  RigidBody part = whole;
  part.range = range;
  for (auto [from, to] : {std::pair{&whole.dx0, &part.dx0}, std::pair{&whole.dy0, &part.dy0},
                          std::pair{&whole.dz0, &part.dz0}}) {
    if (from->empty()) continue;
    to->resize(places.size());
    for (std::size_t k = 0; k < places.size(); ++k) (*to)[k] = (*from)[places[k]];
  }
  return part;
}

void project_rigid_body(ParticleStore& p, RigidBody& body, double t, double dt,
                        bool with_rotation) {
  const ProjectionTerms term(p, body, with_rotation);
  advance_rigid_body(p, body, ordered_sum<kProjectionSums>(body.range.begin, body.range.end, term),
                     t, dt, with_rotation);
}

void advance_rigid_body(ParticleStore& p, RigidBody& body,
                        const std::array<double, kProjectionSums>& sums, double t, double dt,
                        bool with_rotation) {
  if (body.dimension == 3) return advance_in_space(p, body, sums, t, dt, with_rotation);
  const double px = sums[0], py = sums[1], lz = sums[2];
  // Without particle spins (models without rotation) only the orbital part counts.
  const double inertia = body.orbital_inertia + (with_rotation ? body.spin_inertia : 0.0);
  if (body.motion.on) {
    const PrescribedMotion& m = body.motion;
    const double f = m.factor(t, dt);
    const double vx = f * m.velocity[0], vy = f * m.velocity[1], omega = f * m.spin[2];
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
  if (p.dimension == 3) return place_in_space(p, body, with_rotation);
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
