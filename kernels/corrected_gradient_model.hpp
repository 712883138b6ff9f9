#pragma once
// The models built on the kernel-corrected deformation gradient (MODEL.md
// sections 5 and 7), written once over a material law: a total-Lagrangian F
// per particle, the law's first Piola-Kirchhoff stress P(F), and the
// hourglass penalty. No rotation degree of freedom: F carries the rotation,
// so the step skips half angles and spins.
//
// Set-up, per particle:  A_i = sum_j wl_ij r0_ij (x) r0_ij,   wl_ij = w0_ij / |r0_ij|^2
// Pass 1 (all particles): F_i = (sum_j wl_ij r_ij (x) r0_ij) A_i^-1,  J_i = det F_i,
//   S_i = V P(F_i)
// Pass 1b (consistent hourglass, the default): S_i += Q_i = -1/2 sum_j h_ij g_ij (x) r0_ij
// Pass 2 (moving particles):
//   f_i = sum_j [ wl_ij (S_i A_i^-1 + S_j A_j^-1) r0_ij + h_ij g_ij ],
//   g_ij = r_ij - (F_i + F_j) r0_ij / 2,   h_ij = alpha E_ij V (2 / n0) wl_ij.
// S_i = V dW/dF_i makes the first term exactly -d/dr_i of sum_i V W(F_i); the
// hourglass energy E_hg = sum over bonds of 1/2 h_ij |g_ij|^2 depends on the
// positions through F too, and Q_i = dE_hg/dF_i is that part of its
// gradient (pass 1b needs F_j, so it follows pass 1 for every particle). The
// force is then the exact gradient of the total energy: energy is conserved
// to O(dt). MODEL.md's literal form (F held fixed) is hourglass_form =
// "frozen"; it loses about 0.5 % of the external work on the 11.2 kN rod.
//
// A Law (kernels/finite_strain_model.hpp, kernels/linear_elastic_model.hpp)
// supplies: name (also its case section), rotation_invariant, and
//   piola(f, J, lambda, mu, P, strain, pressure): P(F) and the outputs;
//   energy_density(f, J, lambda, mu): W(F).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/hourglass_options.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

namespace tensor2 {
// Row-major 2x2: m[0] m[1] / m[2] m[3].
inline double det(const double* m) {
  return m[0] * m[3] - m[1] * m[2];
}

// out = m A^-1 (row-major 2x2).
inline void times_a_inv(const double* m, const double* a_inv, double* out) {
  out[0] = m[0] * a_inv[0] + m[1] * a_inv[2];
  out[1] = m[0] * a_inv[1] + m[1] * a_inv[3];
  out[2] = m[2] * a_inv[0] + m[3] * a_inv[2];
  out[3] = m[2] * a_inv[1] + m[3] * a_inv[3];
}
}  // namespace tensor2

template <class Law>
class CorrectedGradientModel {
 public:
  static constexpr const char* name = Law::name;
  static constexpr bool uses_rotation = false;
  static constexpr bool rotation_invariant = Law::rotation_invariant;
  // The hourglass term reads positions: the force pass ends with a barrier
  // before the integration moves them.
  static constexpr bool forces_read_positions = true;
  static constexpr const char* options_section = Law::name;
  static std::vector<OptionSpec> options() { return hourglass_option_table(); }

  // Throws InputError if a particle's neighbourhood cannot define A_i^-1.
  CorrectedGradientModel(const ParticleStore& p, const BondTable& bonds,
                         const OptionValues& options)
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
      const double d = tensor2::det(a);
      // An interior particle has A = (n0 / d) I; neighbours on one line give det A = 0.
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

  // Pass 1 (F, J, S A^-1) and, with the consistent hourglass, pass 1b (Q).
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
      tensor2::times_a_inv(g, ai, f);
      const double jac = tensor2::det(f);
      double stress[4];
      Law::piola(f, jac, p.lambda[i], p.mu[i], stress, p.strain[i], p.pressure[i]);
      for (double& s : stress) s *= volume_;  // S = V P
      tensor2::times_a_inv(stress, ai, &stress_a_[4 * i]);
      jacobian_[i] = jac;
    });
    if (!consistent_hourglass_) return;
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
      tensor2::times_a_inv(q, &a_inv_[4 * i], qa);
      for (int k = 0; k < 4; ++k) stress_a_[4 * i + static_cast<std::size_t>(k)] += qa[k];
    });
  }

  // Pass 2: the force; no torque.
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
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

  // V W(F_i) + 1/4 sum_j h_ij |g_ij|^2 (needs a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    const double density =
        Law::energy_density(&def_grad_[4 * i], jacobian_[i], p.lambda[i], p.mu[i]);
    double hourglass = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto g = hourglass_gap(p, bonds, i, b);
      hourglass += hourglass_[b] * (g[0] * g[0] + g[1] * g[1]);
    }
    // Each bond is seen from both ends: a quarter of h |g|^2 per end.
    return volume_ * density + 0.25 * hourglass;
  }

  // J_i at or below the minimum: a collapsed neighbourhood (needs the strain
  // pass at the current state).
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
  // The law's first Piola-Kirchhoff stress of particle i (row-major).
  std::array<double, 4> stress(const ParticleStore& p, std::size_t i) const {
    std::array<double, 4> piola{};
    double strain = 0, pressure = 0;
    Law::piola(&def_grad_[4 * i], jacobian_[i], p.lambda[i], p.mu[i], piola.data(), strain,
               pressure);
    return piola;
  }

 private:
  static double youngs_modulus(double lambda, double mu) {
    return mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
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
