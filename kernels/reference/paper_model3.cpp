#include "kernels/reference/paper_model3.hpp"

#include "kernels/bond_math.hpp"

namespace mpsolid::reference {

PaperResult3 paper_model_3d(const PaperState3& s) {
  const auto n = static_cast<std::size_t>(s.x.cols());
  const double d = s.dimension;
  PaperResult3 out;
  out.strain.assign(n, 0.0);
  out.pressure.assign(n, 0.0);
  out.force = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(n));
  out.torque = Eigen::Matrix3Xd::Zero(3, static_cast<Eigen::Index>(n));

  struct Bond {
    std::size_t i, j;
    double l0, w0, r;
    Eigen::Vector3d rv, u;
  };
  std::vector<Bond> pairs;
  for (const auto& [i, j] : s.bonds) {
    Bond e{};
    e.i = i;
    e.j = j;
    const auto ci = static_cast<Eigen::Index>(i), cj = static_cast<Eigen::Index>(j);
    const Eigen::Vector3d r0 = s.x0.col(cj) - s.x0.col(ci);
    e.l0 = r0.norm();
    e.w0 = s.re / e.l0 - 1.0;
    e.rv = s.x.col(cj) - s.x.col(ci);
    e.r = e.rv.norm();
    e.u = e.rv - bond_math::mean_rotation(s.q[i], s.q[j]) * r0;  // Eq. 4
    pairs.push_back(e);
  }

  // Eq. 3: the divergence of the displacement over the bond.
  for (const Bond& e : pairs) {
    const double un = e.u.dot(e.rv) / e.r;
    out.strain[e.i] += d / s.n0 * un / e.l0 * e.w0;
    out.strain[e.j] += d / s.n0 * un / e.l0 * e.w0;
  }
  for (std::size_t i = 0; i < n; ++i)
    out.pressure[i] = -s.lambda[static_cast<Eigen::Index>(i)] * out.strain[i];

  // Eq. 5-7 in acceleration form, times the mass.
  for (const Bond& e : pairs) {
    const Eigen::Vector3d unit = e.rv / e.r;
    const Eigen::Vector3d normal = e.u.dot(unit) * unit, shear = e.u - normal;
    const auto ci = static_cast<Eigen::Index>(e.i), cj = static_cast<Eigen::Index>(e.j);
    const double mu = 0.5 * (s.mu[ci] + s.mu[cj]);
    const double p_ij = 0.5 * (out.pressure[e.i] + out.pressure[e.j]);
    for (int end = 0; end < 2; ++end) {
      const Eigen::Index a = end == 0 ? ci : cj;
      const double sign = end == 0 ? 1.0 : -1.0;  // u_ji = -u_ij, r_ji = -r_ij
      const double m = s.mass[a], rho = m / s.volume, c = d / (rho * s.n0);
      const Eigen::Vector3d sn = 2 * mu * sign * normal / e.l0, ss = 2 * mu * sign * shear / e.l0;
      const Eigen::Vector3d accel =
          c * 2 * (sn + ss) / e.l0 * e.w0 - c * 2 * p_ij * sign * e.rv / (e.l0 * e.r) * e.w0;
      out.force.col(a) += m * accel;
      const Eigen::Vector3d fs = m * 2 * d / (rho * s.n0) * ss / e.l0 * e.w0;
      out.torque.col(a) += 0.5 * (sign * e.rv).cross(fs);
    }
  }
  return out;
}

}  // namespace mpsolid::reference
