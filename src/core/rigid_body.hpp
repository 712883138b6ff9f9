#pragma once
// Particle-based rigid bodies, kept exactly rigid (MODEL.md section 2.8):
// after the unconstrained velocity update, the body's translational and
// angular velocity are taken from its particles' linear and angular momentum
// (spins included), the pose is advanced, and every particle is placed from
// the pose. Positions never drift apart over millions of steps.
#include <string>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

// A prescribed motion (a piston, a moving anvil, a wall driven at a given
// speed): the pose's velocity is (vx, vy) and its angular velocity spin,
// times the history's factor at tau = t - start (at rest before start),
// whatever the forces on it.
struct PrescribedMotion {
  bool on = false;
  double vx = 0, vy = 0, spin = 0;  // m/s, rad/s at a factor of 1
  LoadHistory history;
  double start = 0;  // s
  bool operator==(const PrescribedMotion&) const = default;
  // The factor over the step from t to t + dt (its midpoint's).
  double factor(double t, double dt) const {
    const double tau = t + 0.5 * dt - start;
    return tau < 0 ? 0.0 : history.factor(tau);
  }
};

struct RigidBody {
  std::string name;
  Range range;                       // storage range of its particles
  double xg0 = 0, yg0 = 0;           // initial centroid
  double xg = 0, yg = 0, angle = 0;  // pose: centroid and rotation Theta
  double vx = 0, vy = 0, omega = 0;  // velocity of the pose
  std::vector<double> dx0, dy0;      // r0_i - r0_g per particle (body order)
  double orbital_inertia = 0;        // sum m |r_i - r_g|^2 (about the centroid)
  double spin_inertia = 0;           // N I: the particles' own spins
  double mass_total = 0;
  PrescribedMotion motion;  // off: the body moves as its forces say
  // A driven body: the work its driver has done on the rest of the run, the
  // impulse it takes beyond the forces, times the velocity it keeps.
  double work = 0;
};

// Sets the reference offsets, centroid and inertia from the particles' x0, y0.
RigidBody make_rigid_body(const ParticleStore& p, std::string name, Range range);

// Projects the particles' velocities onto a rigid motion and advances the pose
// by dt. Uses the start-of-step positions still stored in p.x, p.y. A driven
// body takes its motion's velocity over the step from time t instead, and
// adds its driver's work.
void project_rigid_body(ParticleStore& p, RigidBody& body, double t, double dt, bool with_rotation);

// Places every particle of the body at the pose with the rigid velocity field
// (and, with rotation, theta = Theta with its half angles).
void place_rigid_particles(ParticleStore& p, const RigidBody& body, bool with_rotation);

}  // namespace mpsolid
