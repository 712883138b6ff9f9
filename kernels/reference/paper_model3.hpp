#pragma once
// The paper's model in 3D, slow and obviously correct: a test oracle for
// 3D kernels. The paper writes its Eq. 3-7 for d = 2 or 3; in 3D each
// particle carries an orientation (a unit quaternion) instead of an angle,
// and a bond's reference vector is turned by the pair's mean rotation, the
// geodesic midpoint of the two orientations, normalize(q_i + q_j) (q_j's
// sign taken so that q_i . q_j >= 0): symmetric in i and j, and for two
// turns about one axis the turn by the mean angle, so a plane motion gives
// the 2D model's u_ij = r_ij - R((theta_i + theta_j) / 2) r0_ij. The torque
// is Eq. 7's (1/2) r_ij x F_s as a vector. A pair loop, each bond once,
// Eigen vectors, no shortcuts.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <cstddef>
#include <utility>
#include <vector>

namespace mpsolid::reference {

struct PaperState3 {
  Eigen::Matrix3Xd x, x0;                                  // positions now and at set-up (m)
  std::vector<Eigen::Quaterniond> q;                       // orientations (unit)
  Eigen::VectorXd mass, lambda, mu;                        // kg, Pa, Pa
  std::vector<std::pair<std::size_t, std::size_t>> bonds;  // i < j, each once
  double re = 0;                                           // bond radius (m)
  double n0 = 0;                                           // sum of w0 over a full neighbourhood
  double volume = 0;                                       // a particle's volume, m / rho (m^3)
  double dimension = 3;                                    // d in Eq. 3 and 5-7
};

struct PaperResult3 {
  std::vector<double> strain, pressure;
  Eigen::Matrix3Xd force, torque;  // N, N m per particle
};

PaperResult3 paper_model_3d(const PaperState3& s);

}  // namespace mpsolid::reference
