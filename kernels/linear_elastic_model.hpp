#pragma once
// The linear-elastic model (MODEL.md section 7): small-strain Hooke's law on
// the kernel-corrected deformation gradient of the finite-strain model
// (MODEL.md section 5), what a linear finite-element code computes. No
// rotation degree of freedom, and not rotation invariant: a rigid rotation by
// a gives eps = (cos a - 1) I.
//
// Set-up, per particle:  A_i = sum_j wl_ij r0_ij (x) r0_ij,   wl_ij = w0_ij / |r0_ij|^2
// Pass 1 (all particles): F_i = (sum_j wl_ij r_ij (x) r0_ij) A_i^-1,  J_i = det F_i,
//   eps_i = (F_i + F_i^T) / 2 - I,   sigma_i = lambda_i tr(eps_i) I + 2 mu_i eps_i,
//   S_i = V sigma_i
// Pass 1b (consistent hourglass, the default): S_i += Q_i = -1/2 sum_j h_ij g_ij (x) r0_ij
// Pass 2 (moving particles):
//   f_i = sum_j [ wl_ij (S_i A_i^-1 + S_j A_j^-1) r0_ij + h_ij g_ij ],
//   g_ij = r_ij - (F_i + F_j) r0_ij / 2,   h_ij = alpha E_ij V (2 / n0) wl_ij.
// dW_i/dF_i = V sigma_i for W_i = V (lambda/2 (tr eps_i)^2 + mu eps_i : eps_i)
// (sigma is symmetric), so the force is the exact negative gradient of
// sum_i W_i + E_hg, E_hg = sum over bonds of 1/2 h_ij |g_ij|^2: energy is
// conserved to O(dt) and linear momentum to round-off, angular momentum not.
// Outputs: strain = tr eps, pressure = -(lambda + mu) tr eps (minus the
// in-plane mean stress). The hourglass options are finite_strain's, in the
// case section "linear_elastic".
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kernels/hourglass_options.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

class LinearElasticModel {
 public:
  static constexpr const char* name = "linear_elastic";
  static constexpr bool uses_rotation = false;
  static constexpr bool rotation_invariant = false;  // spurious strain ~ -a^2 / 2
  static constexpr const char* options_section = "linear_elastic";
  static std::vector<OptionSpec> options() { return hourglass_option_table(); }

  // MODEL.md section 7 (set-up as section 5.1). Throws InputError if a
  // particle's neighbourhood cannot define A_i^-1.
  LinearElasticModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options)
      : volume_(bonds.geometry.volume) {
    const HourglassSettings hourglass = hourglass_settings(options);
    consistent_hourglass_ = hourglass.consistent && hourglass.alpha > 0;
    const std::size_t n = p.size();
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
        hourglass_[b] = hourglass.alpha * e_ij * volume_ * (2.0 / n0) * wl;
      }
      const double d = det(a);
      // Neighbours on one line give det A = 0 (MODEL.md section 5.1).
      if (!(std::abs(d) > 1e-8 * (a[0] * a[0] + a[3] * a[3])))
        throw InputError(fmt::format(
            "{}: particle {} at ({}, {}) m has no neighbours off one line, so its "
            "deformation gradient is undefined; make every body at least 2 particles thick",
            name, p.id[i], p.x0[i], p.y0[i]));
      double* inv = &a_inv_[4 * i];
      inv[0] = a[3] / d;
      inv[1] = -a[1] / d;
      inv[2] = -a[2] / d;
      inv[3] = a[0] / d;
    }
  }

  // Pass 1 (F, J, sigma) and, with the consistent hourglass, pass 1b (Q).
  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
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
      const double* ai = &a_inv_[4 * i];
      double* f = &def_grad_[4 * i];
      times_a_inv(g, ai, f);
      const std::array<double, 4> sigma = hooke(f, p.lambda[i], p.mu[i]);
      double s[4];
      for (int k = 0; k < 4; ++k) s[k] = volume_ * sigma[static_cast<std::size_t>(k)];
      times_a_inv(s, ai, &stress_a_[4 * i]);
      jacobian_[i] = det(f);
      const double trace = f[0] + f[3] - 2.0;  // tr eps
      p.strain[i] = trace;
      p.pressure[i] = -(p.lambda[i] + p.mu[i]) * trace;
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
      times_a_inv(q, &a_inv_[4 * i], qa);
      for (int k = 0; k < 4; ++k) stress_a_[4 * i + static_cast<std::size_t>(k)] += qa[k];
    });
  }

  // Pass 2: the force of MODEL.md section 7; no torque.
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      const double* sai = &stress_a_[4 * i];
      double fx = 0.0, fy = 0.0;
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const double* saj = &stress_a_[4 * j];
        const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
        const double wl = wl_[b];
        fx += wl * ((sai[0] + saj[0]) * r0x + (sai[1] + saj[1]) * r0y);
        fy += wl * ((sai[2] + saj[2]) * r0x + (sai[3] + saj[3]) * r0y);
        const auto g = hourglass_gap(p, bonds, i, b);
        fx += hourglass_[b] * g[0];
        fy += hourglass_[b] * g[1];
      }
      p.fx[i] = fx;
      p.fy[i] = fy;
      p.torque[i] = 0.0;
    });
  }

  // W_i + 1/4 sum_j h_ij |g_ij|^2 (MODEL.md section 7).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    const double* f = &def_grad_[4 * i];
    const double exx = f[0] - 1.0, eyy = f[3] - 1.0, exy = 0.5 * (f[1] + f[2]);
    const double trace = exx + eyy;
    const double density =
        0.5 * p.lambda[i] * trace * trace + p.mu[i] * (exx * exx + eyy * eyy + 2.0 * exy * exy);
    double hourglass = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto g = hourglass_gap(p, bonds, i, b);
      hourglass += hourglass_[b] * (g[0] * g[0] + g[1] * g[1]);
    }
    // Each bond is seen from both ends: a quarter of h |g|^2 per end.
    return volume_ * density + 0.25 * hourglass;
  }

  // J_i at or below the minimum: a collapsed neighbourhood, as finite_strain
  // (needs the strain pass at the current state).
  IntegrityReport check_integrity(const ParticleStore&, const BondTable&,
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

  // Row-major 2x2 tensors per particle, from the last strain pass.
  const std::vector<double>& deformation_gradient() const { return def_grad_; }
  const std::vector<double>& jacobian() const { return jacobian_; }
  // The Cauchy (= first Piola-Kirchhoff, small strain) in-plane stress of
  // particle i, row-major, from the last strain pass.
  std::array<double, 4> stress(const ParticleStore& p, std::size_t i) const {
    return hooke(&def_grad_[4 * i], p.lambda[i], p.mu[i]);
  }

 private:
  // Row-major 2x2: m[0] m[1] / m[2] m[3].
  static double det(const double* m) { return m[0] * m[3] - m[1] * m[2]; }

  // out = m A^-1 (row-major 2x2).
  static void times_a_inv(const double* m, const double* a_inv, double* out) {
    out[0] = m[0] * a_inv[0] + m[1] * a_inv[2];
    out[1] = m[0] * a_inv[1] + m[1] * a_inv[3];
    out[2] = m[2] * a_inv[0] + m[3] * a_inv[2];
    out[3] = m[2] * a_inv[1] + m[3] * a_inv[3];
  }

  static double youngs_modulus(double lambda, double mu) {
    return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
  }

  // sigma = lambda tr(eps) I + 2 mu eps, eps = (F + F^T) / 2 - I.
  static std::array<double, 4> hooke(const double* f, double lambda, double mu) {
    const double exx = f[0] - 1.0, eyy = f[3] - 1.0, exy = 0.5 * (f[1] + f[2]);
    const double volumetric = lambda * (exx + eyy);
    return {volumetric + 2.0 * mu * exx, 2.0 * mu * exy, 2.0 * mu * exy,
            volumetric + 2.0 * mu * eyy};
  }

  // g_ij = r_ij - (F_i + F_j) r0_ij / 2 for bond entry b of particle i.
  std::array<double, 2> hourglass_gap(const ParticleStore& p, const BondTable& bonds, std::size_t i,
                                      std::uint32_t b) const {
    const std::size_t j = bonds.neighbor[b];
    const double* fi = &def_grad_[4 * i];
    const double* fj = &def_grad_[4 * j];
    const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
    return {(p.x[j] - p.x[i]) - 0.5 * ((fi[0] + fj[0]) * r0x + (fi[1] + fj[1]) * r0y),
            (p.y[j] - p.y[i]) - 0.5 * ((fi[2] + fj[2]) * r0x + (fi[3] + fj[3]) * r0y)};
  }

  double volume_;
  bool consistent_hourglass_ = false;
  std::vector<double> a_inv_;      // A_i^-1, 4 per particle
  std::vector<double> def_grad_;   // F_i, 4 per particle
  std::vector<double> stress_a_;   // (S_i + Q_i) A_i^-1, 4 per particle
  std::vector<double> jacobian_;   // J_i
  std::vector<double> wl_;         // wl_ij = w0_ij / |r0_ij|^2 per bond entry
  std::vector<double> hourglass_;  // h_ij = alpha E_ij V (2 / n0) wl_ij per bond entry
};

}  // namespace mpsolid
