#pragma once
// Particle-based rigid bodies, kept exactly rigid (MODEL.md sections 2.8 and
// 10): after the unconstrained velocity update, the body's translational and
// angular velocity are taken from its particles' linear and angular momentum
// (spins included), the pose is advanced, and every particle is placed from
// the pose. Positions never drift apart over millions of steps. In space the
// orientation is a quaternion and the rotation over a step the exact
// torque-free splitting of rigid_rotation3.hpp about the principal axes.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

// A prescribed motion (a piston, a moving anvil, a wall driven at a given
// speed): the pose's velocity and its angular velocity (in the plane about z
// only: spin[2]), times the history's factor at tau = t - start (at rest
// before start), whatever the forces on it.
struct PrescribedMotion {
  bool on = false;
  std::array<double, 3> velocity{};  // m/s at a factor of 1
  std::array<double, 3> spin{};      // rad/s at a factor of 1
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
  Range range;        // storage range of its particles
  int dimension = 2;  // 2 (the plane) or 3
  // The pose and its velocity.
  double xg0 = 0, yg0 = 0, zg0 = 0;  // initial centroid
  double xg = 0, yg = 0, zg = 0;     // centroid
  double angle = 0;                  // in the plane: the rotation Theta
  // In space: the principal frame's orientation (w, x, y, z), turning the
  // body's principal axes to the world; `axes` at the start.
  std::array<double, 4> frame{1, 0, 0, 0};
  double vx = 0, vy = 0, vz = 0;
  double omega_x = 0, omega_y = 0, omega = 0;  // angular velocity (the plane's about z)
  // In space: the angular momentum about the centroid (the particles' spins
  // included where the model has them), kept as state and changed only by
  // the impulse the particles take, so that a free body keeps it exactly.
  std::array<double, 3> angular_momentum{};
  // The body's make-up.
  std::vector<double> dx0, dy0, dz0;  // r0_i - r0_g per particle (body order)
  double orbital_inertia = 0;         // in the plane: sum m |r_i - r_g|^2
  // In space: the principal moments of sum m (|r|^2 1 - r r^T) about the
  // centroid (ascending), and its principal axes at the start (w, x, y, z).
  std::array<double, 3> orbital_moments{};
  std::array<double, 4> axes{1, 0, 0, 0};
  double spin_inertia = 0;  // N I: the particles' own spins (isotropic)
  double mass_total = 0;
  PrescribedMotion motion;  // off: the body moves as its forces say
  // A driven body: the work its driver has done on the rest of the run, the
  // impulse it takes beyond the forces, times the velocity it keeps.
  double work = 0;
};

// The pose and its velocity as doubles, the order checkpoints, slices and
// hashes keep them: in the plane x, y, Theta, vx, vy, omega; in space x, y,
// z, the frame (w, x, y, z), vx, vy, vz, omega_x, omega_y, omega_z and the
// angular momentum's x, y, z.
std::size_t pose_size(int dimension);
std::vector<double> pose_values(const RigidBody& body);
void set_pose_values(RigidBody& body, const double* values);

// In space: the rotation from the start, frame * axes^-1 (w, x, y, z).
std::array<double, 4> rotation_from_start(const RigidBody& body);

// Sets the reference offsets, centroid and inertia from the particles' x0,
// y0 (and z0 in space).
RigidBody make_rigid_body(const ParticleStore& p, std::string name, Range range);

// Sets the body's velocity and angular velocity (the plane's about z:
// spin[2]), with, in space, its angular momentum; places its particles.
void set_rigid_motion(ParticleStore& p, RigidBody& body, const double velocity[3],
                      const double spin[3], bool with_rotation);

// Projects the particles' velocities onto a rigid motion and advances the pose
// by dt. Uses the start-of-step positions still stored in p.x, p.y. A driven
// body takes its motion's velocity over the step from time t instead, and
// adds its driver's work.
void project_rigid_body(ParticleStore& p, RigidBody& body, double t, double dt, bool with_rotation);

// Places every particle of the body at the pose with the rigid velocity field
// (and, with rotation, each particle's orientation and spin the body's).
void place_rigid_particles(ParticleStore& p, const RigidBody& body, bool with_rotation);

}  // namespace mpsolid
