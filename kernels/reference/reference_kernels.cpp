#include "kernels/reference/reference_kernels.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "kernels/model_common.hpp"

namespace mpsolid::reference {

PaperResult paper_model(const ParticleStore& p, const BondTable& bonds, bool energy_consistent) {
  const std::size_t n = p.size();
  const double d = 2.0, re = bonds.geometry.re, n0 = number_density(bonds);
  PaperResult out;
  out.strain.assign(n, 0.0);
  out.pressure.assign(n, 0.0);
  out.fx.assign(n, 0.0);
  out.fy.assign(n, 0.0);
  out.torque.assign(n, 0.0);

  struct Bond {
    std::size_t i, j;
    double r0x, r0y, l0, w0;
    double ux, uy, rx, ry, r;
  };
  std::vector<Bond> pairs;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      if (j < i) continue;
      Bond e{};
      e.i = i;
      e.j = j;
      e.r0x = p.x0[j] - p.x0[i];
      e.r0y = p.y0[j] - p.y0[i];
      e.l0 = std::hypot(e.r0x, e.r0y);
      e.w0 = re / e.l0 - 1.0;
      const double th = 0.5 * (p.theta[i] + p.theta[j]);
      e.rx = p.x[j] - p.x[i];
      e.ry = p.y[j] - p.y[i];
      e.r = std::hypot(e.rx, e.ry);
      e.ux = e.rx - (std::cos(th) * e.r0x - std::sin(th) * e.r0y);
      e.uy = e.ry - (std::sin(th) * e.r0x + std::cos(th) * e.r0y);
      pairs.push_back(e);
    }

  // Eq. 3: divergence of the displacement over the bond (u_j - u_i = u_ij).
  for (const Bond& e : pairs) {
    const double un = (e.ux * e.rx + e.uy * e.ry) / e.r;  // u_ij . e_ij; u_ji . e_ji is the same
    out.strain[e.i] += d / n0 * un / e.l0 * e.w0;
    out.strain[e.j] += d / n0 * un / e.l0 * e.w0;
  }
  for (std::size_t i = 0; i < n; ++i) out.pressure[i] = -p.lambda[i] * out.strain[i];

  // Eq. 5-7, per particle in acceleration form, then times the mass.
  for (const Bond& e : pairs) {
    const double ex = e.rx / e.r, ey = e.ry / e.r;
    const double un = e.ux * ex + e.uy * ey;
    const double unx = un * ex, uny = un * ey;        // normal part of u_ij
    const double usx = e.ux - unx, usy = e.uy - uny;  // shear part
    const double mu = 0.5 * (p.mu[e.i] + p.mu[e.j]);
    const double p_ij = 0.5 * (out.pressure[e.i] + out.pressure[e.j]);
    for (int end = 0; end < 2; ++end) {
      const std::size_t a = end == 0 ? e.i : e.j;
      const double sign = end == 0 ? 1.0 : -1.0;  // u_ji = -u_ij, r_ji = -r_ij
      const double m = 1.0 / p.inv_mass[a];
      const double rho = m / bonds.geometry.volume;  // m = rho l0^2 D
      const double sn_x = 2 * mu * sign * unx / e.l0, sn_y = 2 * mu * sign * uny / e.l0;
      const double ss_x = 2 * mu * sign * usx / e.l0, ss_y = 2 * mu * sign * usy / e.l0;
      const double c = d / (rho * n0);
      const double ax =
          c * 2 * (sn_x + ss_x) / e.l0 * e.w0 - c * 2 * p_ij * sign * e.rx / (e.l0 * e.r) * e.w0;
      const double ay =
          c * 2 * (sn_y + ss_y) / e.l0 * e.w0 - c * 2 * p_ij * sign * e.ry / (e.l0 * e.r) * e.w0;
      out.fx[a] += m * ax;
      out.fy[a] += m * ay;
      // Eq. 7: F_s = m (2d / (rho n0)) sigma_s / |r0| w0; I domega/dt = 1/2 sum r x F_s.
      const double fsx = m * 2 * d / (rho * n0) * ss_x / e.l0 * e.w0;
      const double fsy = m * 2 * d / (rho * n0) * ss_y / e.l0 * e.w0;
      out.torque[a] += 0.5 * (sign * e.rx * fsy - sign * e.ry * fsx);
    }
    if (energy_consistent) {
      const double c = bonds.geometry.volume * (d / n0) * e.w0 *
                       (out.pressure[e.i] + out.pressure[e.j]) / (e.l0 * e.r);
      out.fx[e.i] -= c * usx;
      out.fy[e.i] -= c * usy;
      out.fx[e.j] += c * usx;
      out.fy[e.j] += c * usy;
      const double t = 0.5 * c * e.r * (e.ux * ey - e.uy * ex);
      out.torque[e.i] += t;
      out.torque[e.j] += t;
    }
  }
  return out;
}

GradientLaw neo_hookean_law() {
  return {[](const Eigen::Matrix2d& f, double lambda, double mu) {
            const Eigen::Matrix2d fit = f.inverse().transpose();
            return Eigen::Matrix2d(mu * (f - fit) + lambda * std::log(f.determinant()) * fit);
          },
          [](const Eigen::Matrix2d& f, double lambda, double mu) {
            const double log_j = std::log(f.determinant());
            return 0.5 * mu * ((f.transpose() * f).trace() - 2.0) - mu * log_j +
                   0.5 * lambda * log_j * log_j;
          }};
}

GradientLaw hooke_law() {
  auto strain = [](const Eigen::Matrix2d& f) {
    return Eigen::Matrix2d(0.5 * (f + f.transpose()) - Eigen::Matrix2d::Identity());
  };
  return {
      [strain](const Eigen::Matrix2d& f, double lambda, double mu) {
        const Eigen::Matrix2d eps = strain(f);
        return Eigen::Matrix2d(lambda * eps.trace() * Eigen::Matrix2d::Identity() + 2 * mu * eps);
      },
      [strain](const Eigen::Matrix2d& f, double lambda, double mu) {
        const Eigen::Matrix2d eps = strain(f);
        return 0.5 * lambda * eps.trace() * eps.trace() + mu * eps.array().square().sum();
      }};
}

GradientResult corrected_gradient_model(const ParticleStore& p, const BondTable& bonds,
                                        const GradientLaw& law, double hourglass, bool consistent) {
  using Eigen::Matrix2d;
  using Eigen::Vector2d;
  const std::size_t n = p.size();
  const double re = bonds.geometry.re, n0 = number_density(bonds), volume = bonds.geometry.volume;
  auto r0 = [&](std::size_t i, std::size_t j) {
    return Vector2d(p.x0[j] - p.x0[i], p.y0[j] - p.y0[i]);
  };
  auto r = [&](std::size_t i, std::size_t j) { return Vector2d(p.x[j] - p.x[i], p.y[j] - p.y[i]); };
  auto wl = [&](std::size_t i, std::size_t j) {
    const double len = r0(i, j).norm();
    return (re / len - 1.0) / (len * len);
  };
  auto young = [&](std::size_t i) {
    return p.mu[i] * (3 * p.lambda[i] + 2 * p.mu[i]) / (p.lambda[i] + p.mu[i]);
  };
  std::vector<Matrix2d> a_inv(n), f(n), s(n);
  GradientResult out;
  out.piola.resize(n);
  out.def_grad.resize(4 * n);
  out.jacobian.resize(n);
  out.fx.assign(n, 0.0);
  out.fy.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    Matrix2d a = Matrix2d::Zero(), g = Matrix2d::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      a += wl(i, j) * r0(i, j) * r0(i, j).transpose();
      g += wl(i, j) * r(i, j) * r0(i, j).transpose();
    }
    a_inv[i] = a.inverse();
    f[i] = g * a_inv[i];
    out.piola[i] = law.piola(f[i], p.lambda[i], p.mu[i]);
    s[i] = volume * out.piola[i];
    out.energy += volume * law.energy_density(f[i], p.lambda[i], p.mu[i]);
    out.jacobian[i] = f[i].determinant();
    for (int k = 0; k < 4; ++k)
      out.def_grad[4 * i + static_cast<std::size_t>(k)] = f[i](k / 2, k % 2);
  }
  auto h = [&](std::size_t i, std::size_t j) {
    return hourglass * 0.5 * (young(i) + young(j)) * volume * (2.0 / n0) * wl(i, j);
  };
  auto gap = [&](std::size_t i, std::size_t j) {
    return Vector2d(r(i, j) - 0.5 * (f[i] + f[j]) * r0(i, j));
  };
  if (consistent)
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        s[i] += -0.5 * h(i, j) * gap(i, j) * r0(i, j).transpose();
      }
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      if (j < i) continue;
      const Vector2d force =
          wl(i, j) * (s[i] * a_inv[i] + s[j] * a_inv[j]) * r0(i, j) + h(i, j) * gap(i, j);
      out.fx[i] += force.x();
      out.fy[i] += force.y();
      out.fx[j] -= force.x();
      out.fy[j] -= force.y();
      out.energy += 0.5 * h(i, j) * gap(i, j).squaredNorm();
    }
  return out;
}

}  // namespace mpsolid::reference
