#include "src/core/rigid_rotation3.hpp"

#include <Eigen/Eigenvalues>

namespace mpsolid {

PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  PrincipalAxes out{solver.eigenvalues(), solver.eigenvectors()};
  if (out.axes.determinant() < 0) out.axes.col(2) = -out.axes.col(2);  // right-handed
  return out;
}

Eigen::Matrix3d inertia_tensor(const Eigen::Matrix3Xd& positions, const Eigen::VectorXd& masses,
                               const Eigen::Vector3d& centroid,
                               const Eigen::VectorXd& spin_inertia) {
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < positions.cols(); ++i) {
    const Eigen::Vector3d r = positions.col(i) - centroid;
    inertia += masses[i] * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
    inertia.diagonal().array() += spin_inertia[i];
  }
  return inertia;
}

void rotate_free(Eigen::Quaterniond& q, Eigen::Vector3d& body_momentum,
                 const Eigen::Vector3d& moments, double dt) {
  // The body turns by phi = h Pi_a / I_a about its axis a; its momentum in
  // its own frame turns back by the same angle, Pi_a unchanged.
  const auto about = [&](int a, double h) {
    const double phi = h * body_momentum[a] / moments[a];
    const Eigen::AngleAxisd turn(phi, Eigen::Vector3d::Unit(a));
    q = q * Eigen::Quaterniond(turn);
    body_momentum = turn.inverse() * body_momentum;
  };
  about(0, 0.5 * dt);
  about(1, 0.5 * dt);
  about(2, dt);
  about(1, 0.5 * dt);
  about(0, 0.5 * dt);
  q.normalize();
}

}  // namespace mpsolid
