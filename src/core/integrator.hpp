#pragma once
// Symplectic Euler (the paper's Eq. 8-9): the new velocity moves the position.
// Serial over the range: the step calls these on each thread's block.
#include <Eigen/Geometry>

#include "src/core/particle_store.hpp"

namespace mpsolid {

// v += dt f / m, r += dt v; with rotation also omega += dt tau / I,
// theta += dt omega and the new half angles (so the next step needs no
// separate half-angle pass); in space the orientation quaternion turned by
// omega dt instead.
void kick_drift(ParticleStore& p, Range range, double dt, bool with_rotation);

// In space: q turned by the rotation vector `turn` (rad) about the fixed
// axes, exp(turn / 2) q, normalised; q itself for no turn.
inline Eigen::Quaterniond turned(const Eigen::Quaterniond& q, const Eigen::Vector3d& turn) {
  const double angle = turn.norm();
  if (angle == 0.0) return q;
  return (Eigen::Quaterniond(Eigen::AngleAxisd(angle, turn / angle)) * q).normalized();
}

// Velocity update only (rigid particles: their pose update places them).
void kick(ParticleStore& p, Range range, double dt, bool with_rotation);

}  // namespace mpsolid
