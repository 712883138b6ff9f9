#pragma once
// Per-bond maths of the elastic MPS model, with MODEL.md's names. Every kernel
// and every test calls these; nothing else spells the formulas out.
//
//   w(r)        = re / r - 1                      (0 < r < re), else 0
//   theta_ij    = (theta_i + theta_j) / 2, from half angles c = cos(theta/2),
//                 s = sin(theta/2):  cos theta_ij = c_i c_j - s_i s_j,
//                                    sin theta_ij = s_i c_j + c_i s_j
//   r_ij        = r_j - r_i
//   u_ij        = r_ij - R(theta_ij) r0_ij        (rotation-corrected displacement)
//
// Every operation is symmetric under i <-> j, so u_ji = -u_ij bit for bit
// (with -ffp-contract=off).
#include <Eigen/Geometry>
#include <cmath>

#include "src/core/types.hpp"

namespace mpsolid::bond_math {

inline double weight(double r, double re) {
  return (r > 0.0 && r < re) ? re / r - 1.0 : 0.0;
}

// n0 = sum_j w(|r0_ij|) over a full square-lattice neighbourhood of spacing l0.
inline double lattice_number_density(double l0, double re) {
  double n0 = 0.0;
  const int reach = static_cast<int>(std::ceil(re / l0));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      n0 += weight(l0 * std::sqrt(static_cast<double>(a * a + b * b)), re);
  return n0;
}

// The same over a full cubic-lattice neighbourhood (3D).
inline double lattice_number_density_3d(double l0, double re) {
  double n0 = 0.0;
  const int reach = static_cast<int>(std::ceil(re / l0));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b)
      for (int c = -reach; c <= reach; ++c)
        n0 += weight(l0 * std::sqrt(static_cast<double>(a * a + b * b + c * c)), re);
  return n0;
}

using ::mpsolid::cross;

// T: double, or a vector of lanes (kernels/lanes.hpp) computing lane by lane.
template <class T>
struct Rotation {
  T cos, sin;
};

// Rotation by theta_ij = (theta_i + theta_j) / 2 from the two half angles.
template <class T>
inline Rotation<T> bond_rotation(T ci, T si, T cj, T sj) {
  return {ci * cj - si * sj, si * cj + ci * sj};
}

template <class T>
struct BondVectors {
  T rx, ry;  // r_ij = r_j - r_i
  T ux, uy;  // u_ij = r_ij - R(theta_ij) r0_ij
};

template <class T>
inline BondVectors<T> bond_vectors(T xi, T yi, T xj, T yj, Rotation<T> rot, T r0x, T r0y) {
  const T rx = xj - xi;
  const T ry = yj - yi;
  return {rx, ry, rx - (rot.cos * r0x - rot.sin * r0y), ry - (rot.sin * r0x + rot.cos * r0y)};
}

// Normal extension u_ij . e_ij with e_ij = r_ij / |r_ij|.
template <class T>
inline T normal_extension(const BondVectors<T>& b, T inv_length) {
  return (b.ux * b.rx + b.uy * b.ry) * inv_length;
}

// In space, the pair's mean rotation: the geodesic midpoint of the two
// orientations, normalize(q_i + s q_j) with s = +-1 making q_i . s q_j >= 0
// (q and -q are one orientation). Symmetric in i and j (from the other end
// the same or the negated quaternion: the same rotation, bit for bit); for
// turns about one axis, the turn by the mean angle (MODEL.md section 10).
inline Eigen::Quaterniond mean_rotation(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const double side = a.dot(b) < 0 ? -1.0 : 1.0;
  Eigen::Quaterniond m;
  m.coeffs() = a.coeffs() + side * b.coeffs();
  return m.normalized();
}

}  // namespace mpsolid::bond_math
