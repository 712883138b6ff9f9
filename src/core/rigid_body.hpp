#pragma once
// Particle-based rigid bodies, kept exactly rigid (MODEL.md sections 2.8 and
// 10): after the unconstrained velocity update, the body's translational and
// angular velocity are taken from its particles' linear and angular momentum
// (spins included), the pose is advanced, and every particle is placed from
// the pose. Positions never drift apart over millions of steps. In space the
// orientation is a quaternion and the rotation over a step the exact
// torque-free splitting of rigid_rotation3.hpp about the principal axes.
#include <Eigen/Core>
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

// The part of a body split between ranks one rank holds: its pose and
// make-up, with `range` the rank's own particles of it (storage range here)
// and their offsets, the k-th the whole body's `places[k]`-th.
RigidBody rigid_body_part(const RigidBody& whole, Range range,
                          const std::vector<std::size_t>& places);

// Sets the body's velocity and angular velocity (the plane's about z:
// spin[2]), with, in space, its angular momentum; places its particles.
void set_rigid_motion(ParticleStore& p, RigidBody& body, const double velocity[3],
                      const double spin[3], bool with_rotation);

// Projects the particles' velocities onto a rigid motion and advances the pose
// by dt. Uses the start-of-step positions still stored in p.x, p.y. A driven
// body takes its motion's velocity over the step from time t instead, and
// adds its driver's work. It is the ordered sum of ProjectionTerms over the
// body's particles followed by advance_rigid_body.
void project_rigid_body(ParticleStore& p, RigidBody& body, double t, double dt, bool with_rotation);

// The projection's sums per particle: in the plane the linear momentum and
// the angular momentum about the centroid (then three zeros); in space the
// impulse beyond the rigid field the particles were placed with, linear and
// angular. A body split between ranks adds them over the ranks in the
// serial order (src/solver/split_rigid_bodies.hpp), each rank over its own
// particles, which `range` and the offsets then cover.
inline constexpr std::size_t kProjectionSums = 6;
class ProjectionTerms {
 public:
  ProjectionTerms(const ParticleStore& p, const RigidBody& body, bool with_rotation);
  // Particle i of the store (the body's i - range.begin-th here).
  std::array<double, kProjectionSums> operator()(std::size_t i) const;

 private:
  const ParticleStore& p_;
  const RigidBody& body_;
  bool with_rotation_;
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();  // in space: from the start
  std::array<double, 3> w_old_{};
};

// Advances the pose from the projection's sums over the whole body and
// places the particles `range` covers.
void advance_rigid_body(ParticleStore& p, RigidBody& body,
                        const std::array<double, kProjectionSums>& sums, double t, double dt,
                        bool with_rotation);

// Places every particle of the body at the pose with the rigid velocity field
// (and, with rotation, each particle's orientation and spin the body's).
void place_rigid_particles(ParticleStore& p, const RigidBody& body, bool with_rotation);

}  // namespace mpsolid
