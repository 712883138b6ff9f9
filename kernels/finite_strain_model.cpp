#include "kernels/finite_strain_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "src/core/parallel.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

namespace {
// Row-major 2x2: m[0] m[1] / m[2] m[3].
inline double det(const double* m) {
  return m[0] * m[3] - m[1] * m[2];
}

// out = m A^-1 (row-major 2x2).
inline void store_times_a_inv(const double* m, const double* a_inv, double* out) {
  out[0] = m[0] * a_inv[0] + m[1] * a_inv[2];
  out[1] = m[0] * a_inv[1] + m[1] * a_inv[3];
  out[2] = m[2] * a_inv[0] + m[3] * a_inv[2];
  out[3] = m[2] * a_inv[1] + m[3] * a_inv[3];
}

inline double youngs_modulus(double lambda, double mu) {
  return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
}
}  // namespace

FiniteStrainModel::FiniteStrainModel(const ParticleStore& p, const BondTable& bonds,
                                     const OptionValues& options)
    : volume_(bonds.geometry.volume) {
  const HourglassSettings hourglass = hourglass_settings(options);
  consistent_hourglass_ = hourglass.consistent && hourglass.alpha > 0;
  const std::size_t n = p.size();
  const double volume = volume_;
  const double n0 = number_density(bonds);
  a_inv_.assign(4 * n, 0.0);
  def_grad_.assign(4 * n, 0.0);
  stress_a_.assign(4 * n, 0.0);
  jacobian_.assign(n, 1.0);
  wl_.resize(bonds.entry_count());
  hourglass_.resize(bonds.entry_count());
  for (std::size_t i = 0; i < n; ++i) {
    double a[4] = {0, 0, 0, 0};
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
      const double len2 = r0x * r0x + r0y * r0y;
      const double wl = bond_math::weight(std::sqrt(len2), bonds.geometry.re) / len2;
      a[0] += wl * r0x * r0x;
      a[1] += wl * r0x * r0y;
      a[2] += wl * r0y * r0x;
      a[3] += wl * r0y * r0y;
      const double e_ij =
          0.5 * (youngs_modulus(p.lambda[i], p.mu[i]) + youngs_modulus(p.lambda[j], p.mu[j]));
      wl_[b] = wl;
      hourglass_[b] = hourglass.alpha * e_ij * volume * (2.0 / n0) * wl;
    }
    const double d = det(a);
    // An interior particle has A = (n0 / d) I; neighbours on one line give det A = 0.
    if (!(std::abs(d) > 1e-8 * (a[0] * a[0] + a[3] * a[3])))
      throw InputError(fmt::format(
          "finite_strain: particle {} at ({}, {}) m has no neighbours off one line, so its "
          "deformation gradient is undefined; make every body at least 2 particles thick",
          p.id[i], p.x0[i], p.y0[i]));
    double* inv = &a_inv_[4 * i];
    inv[0] = a[3] / d;
    inv[1] = -a[1] / d;
    inv[2] = -a[2] / d;
    inv[3] = a[0] / d;
  }
}

void FiniteStrainModel::compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
  parallel_for(range.begin, range.end, [&](std::size_t i) {
    const double xi = p.x[i], yi = p.y[i];
    double g[4] = {0, 0, 0, 0};  // sum_j wl r_ij (x) r0_ij
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const double w = wl_[b];
      const double rx = p.x[j] - xi, ry = p.y[j] - yi;
      g[0] += w * rx * bonds.r0x[b];
      g[1] += w * rx * bonds.r0y[b];
      g[2] += w * ry * bonds.r0x[b];
      g[3] += w * ry * bonds.r0y[b];
    }
    const double volume = volume_;
    const double* ai = &a_inv_[4 * i];
    double* f = &def_grad_[4 * i];
    store_times_a_inv(g, ai, f);
    const double jac = det(f);
    const double log_j = std::log(jac);
    // F^-T = (1 / J) [[f3, -f2], [-f1, f0]]
    const double fit[4] = {f[3] / jac, -f[2] / jac, -f[1] / jac, f[0] / jac};
    const double mu = p.mu[i], lambda = p.lambda[i];
    double stress[4];
    for (int k = 0; k < 4; ++k) stress[k] = mu * (f[k] - fit[k]) + lambda * log_j * fit[k];
    for (double& s : stress) s *= volume;  // S = V P
    store_times_a_inv(stress, ai, &stress_a_[4 * i]);
    jacobian_[i] = jac;
    p.strain[i] = log_j;
    p.pressure[i] = -lambda * log_j / jac;
  });
  if (!consistent_hourglass_) return;
  // Pass 1b: Q_i = -1/2 sum_j h_ij g_ij (x) r0_ij, added to S_i. Reads F of
  // the neighbours, so it follows pass 1 for every particle.
  parallel_for(range.begin, range.end, [&](std::size_t i) {
    double q[4] = {0, 0, 0, 0};
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto g = hourglass_gap(p, bonds, i, b);
      const double h = -0.5 * hourglass_[b];
      q[0] += h * g[0] * bonds.r0x[b];
      q[1] += h * g[0] * bonds.r0y[b];
      q[2] += h * g[1] * bonds.r0x[b];
      q[3] += h * g[1] * bonds.r0y[b];
    }
    double qa[4];
    store_times_a_inv(q, &a_inv_[4 * i], qa);
    for (int k = 0; k < 4; ++k) stress_a_[4 * i + static_cast<std::size_t>(k)] += qa[k];
  });
}

std::array<double, 2> FiniteStrainModel::hourglass_gap(const ParticleStore& p,
                                                       const BondTable& bonds, std::size_t i,
                                                       std::uint32_t b) const {
  const std::size_t j = bonds.neighbor[b];
  const double* fi = &def_grad_[4 * i];
  const double* fj = &def_grad_[4 * j];
  const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
  return {(p.x[j] - p.x[i]) - 0.5 * ((fi[0] + fj[0]) * r0x + (fi[1] + fj[1]) * r0y),
          (p.y[j] - p.y[i]) - 0.5 * ((fi[2] + fj[2]) * r0x + (fi[3] + fj[3]) * r0y)};
}

void FiniteStrainModel::compute_forces(ParticleStore& p, const BondTable& bonds,
                                       Range range) const {
  parallel_for(range.begin, range.end, [&](std::size_t i) {
    const double* pai = &stress_a_[4 * i];
    double fx = 0.0, fy = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const double* paj = &stress_a_[4 * j];
      const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
      const double wl = wl_[b];
      fx += wl * ((pai[0] + paj[0]) * r0x + (pai[1] + paj[1]) * r0y);
      fy += wl * ((pai[2] + paj[2]) * r0x + (pai[3] + paj[3]) * r0y);
      // Hourglass: the bond's deviation from the mean affine map of its ends.
      const auto g = hourglass_gap(p, bonds, i, b);
      fx += hourglass_[b] * g[0];
      fy += hourglass_[b] * g[1];
    }
    p.fx[i] = fx;
    p.fy[i] = fy;
    p.torque[i] = 0.0;
  });
}

double FiniteStrainModel::particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                                 std::size_t i) const {
  const double* f = &def_grad_[4 * i];
  const double log_j = std::log(jacobian_[i]);
  const double frob = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] + f[3] * f[3];
  const double density =
      0.5 * p.mu[i] * (frob - 2.0) - p.mu[i] * log_j + 0.5 * p.lambda[i] * log_j * log_j;
  double hourglass = 0.0;
  for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
    const auto g = hourglass_gap(p, bonds, i, b);
    hourglass += hourglass_[b] * (g[0] * g[0] + g[1] * g[1]);
  }
  // Each bond is seen from both ends: a quarter of k |g|^2 per end.
  return volume_ * density + 0.25 * hourglass;
}

IntegrityReport FiniteStrainModel::check_integrity(const ParticleStore&, const BondTable&,
                                                   const IntegrityLimits& limits) const {
  IntegrityReport r;
  if (jacobian_.empty()) return r;
  r.particle = index_of_min(jacobian_);
  r.neighbor = r.particle;
  r.value = jacobian_[r.particle];
  r.failed = !(r.value > limits.min_jacobian);
  r.criterion =
      fmt::format("particle neighbourhood collapsed (J = det F <= {})", limits.min_jacobian);
  return r;
}

}  // namespace mpsolid
