#pragma once
// A rigid body's rotation in 3D: its principal axes and moments from its
// particles, and the torque-free rotation over a step by the splitting of
// Dullweber, Leimkuhler and McLachlan (J. Chem. Phys. 107, 1997): exact
// rotations about the body's principal axes in turn (1 and 2 for half the
// step, 3 for all of it, 2 and 1 again). Each piece is an exact rigid
// rotation, so the angular momentum in the world stays what it was (to
// round-off) and the orientation a unit quaternion; the splitting is
// symplectic and time-reversible, so the energy error stays bounded, of
// order dt^2, over any number of steps, and a body spun about its
// intermediate axis flips as it must.
//
// Conventions: q turns the body frame (its principal axes, the moments in
// `moments`) to the world; `body_momentum` is the angular momentum in the
// body frame, L = q body_momentum.
#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace mpsolid {

struct PrincipalAxes {
  Eigen::Vector3d moments;  // kg m^2 (per body, ascending)
  Eigen::Matrix3d axes;     // columns: the axes in the world, right-handed
};

// The principal moments and axes of a symmetric inertia tensor (about the
// centroid).
PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia);

// The inertia tensor about `centroid` of point masses at `positions`
// (3 x n), each also spinning with its own isotropic `spin_inertia`
// (a cubic particle: m l0^2 / 6).
Eigen::Matrix3d inertia_tensor(const Eigen::Matrix3Xd& positions, const Eigen::VectorXd& masses,
                               const Eigen::Vector3d& centroid,
                               const Eigen::VectorXd& spin_inertia);

// The torque-free rotation over dt: q and body_momentum advanced together.
void rotate_free(Eigen::Quaterniond& q, Eigen::Vector3d& body_momentum,
                 const Eigen::Vector3d& moments, double dt);

// The angular velocity in the world of a body at q with body_momentum.
inline Eigen::Vector3d world_angular_velocity(const Eigen::Quaterniond& q,
                                              const Eigen::Vector3d& body_momentum,
                                              const Eigen::Vector3d& moments) {
  return q * body_momentum.cwiseQuotient(moments);
}

}  // namespace mpsolid
