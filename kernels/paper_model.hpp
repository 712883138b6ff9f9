#pragma once
// The paper's elastic MPS model (MODEL.md section 2), as two gather passes,
// and its energy-consistent variant (MODEL.md section 4b).
//
// Pass 1, strain and pressure, for every particle (walls and rigid included):
//   eps_i = (d / n0) sum_j w0_ij (u_ij . e_ij) / |r0_ij|,   p_i = -lambda_i eps_i
// Pass 2, fused force and torque, for the moving particles:
//   f_i   = sum_j k_ij u_ij  -  sum_j C_ij r_ij
//   tau_i = 1/2 sum_j k_ij (r_ij x u_ij)
// with k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (bond + shear stress of
// Eq. 5 fused: sigma^n + sigma^s = 2 mu u / |r0|), V = m / rho = l0^2 D, and
// C_ij = V (d / n0) w0_ij (p_i + p_j) / (|r0_ij| |r_ij|) (Eq. 5's pressure
// term with p_ij = (p_i + p_j) / 2). The torque is the paper's -T_ij / 2
// (Eq. 7): the normal part of u has no moment about r_ij, so r x u^s = r x u.
//
// Energy-consistent variant: the pressure force above is the gradient of
// sum_i 1/2 lambda_i V eps_i^2 only to first order; the missing part of the
// gradient adds, per bond, -C_ij u^s_ij to the force and
// 1/2 C_ij |r_ij| (u_ij x e_ij) = 1/2 C_ij (u_ij x r_ij) to the torque of
// each end.
#include <cmath>
#include <vector>

#include "kernels/bond_loop.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/option_table.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

template <bool EnergyConsistent>
class PaperModelT {
 public:
  static constexpr const char* name = EnergyConsistent ? "paper_conservative" : "paper";
  static constexpr bool uses_rotation = true;
  static constexpr bool rotation_invariant = true;
  static constexpr const char* options_section = "";  // no options
  static std::vector<OptionSpec> options() { return {}; }

  PaperModelT() = default;  // no bonds: only a placeholder to assign a model to
  // The per-bond coefficients (MODEL.md sections 2.3-2.4), mu_ij the
  // arithmetic mean of the two ends' mu.
  PaperModelT(const ParticleStore& p, const BondTable& bonds, const OptionValues&)
      : volume_(bonds.geometry.volume) {
    const double d_over_n0 = kDim / number_density(bonds);
    strain_coef_.resize(bonds.entry_count());
    spring_coef_.resize(bonds.entry_count());
    parallel_for(0, p.size(), [&](std::size_t i) {
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
        const double len = std::sqrt(r0x * r0x + r0y * r0y);
        const double w0 = bond_math::weight(len, bonds.geometry.re);
        const double mu_ij = 0.5 * (p.mu[i] + p.mu[j]);
        strain_coef_[b] = d_over_n0 * w0 / len;
        spring_coef_[b] = volume_ * d_over_n0 * 4.0 * mu_ij * w0 / (len * len);
      }
    });
  }

  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      double eps = 0.0;
      for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double inv_len) {
        eps += strain_coef_[b] * bond_math::normal_extension(v, inv_len);
      });
      p.strain[i] = eps;
      p.pressure[i] = -p.lambda[i] * eps;
    });
  }

  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    const double volume = volume_;
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      const double pi = p.pressure[i];
      double fx = 0.0, fy = 0.0, torque = 0.0;
      for_each_bond(p, bonds, i,
                    [&](std::uint32_t b, std::size_t j, const auto& v, double inv_len) {
                      const double k = spring_coef_[b];
                      const double c = volume * strain_coef_[b] * (pi + p.pressure[j]) * inv_len;
                      fx += k * v.ux - c * v.rx;
                      fy += k * v.uy - c * v.ry;
                      double bond_torque = k * bond_math::cross(v.rx, v.ry, v.ux, v.uy);
                      if constexpr (EnergyConsistent) {
                        // u^s = u - (u . e) e
                        const double un = bond_math::normal_extension(v, inv_len) * inv_len;
                        fx -= c * (v.ux - un * v.rx);
                        fy -= c * (v.uy - un * v.ry);
                        bond_torque += c * bond_math::cross(v.ux, v.uy, v.rx, v.ry);
                      }
                      torque += bond_torque;
                    });
      p.fx[i] = fx;
      p.fy[i] = fy;
      p.torque[i] = 0.5 * torque;
    });
  }

  // Strain energy of particle i (MODEL.md section 4b): its share of
  // sum over bonds (each once) of 1/2 k_ij |u_ij|^2, plus 1/2 lambda_i V eps_i^2.
  // Needs the strain pass at the current state.
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    double bond_energy = 0.0;
    for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double) {
      bond_energy += spring_coef_[b] * (v.ux * v.ux + v.uy * v.uy);
    });
    // Each bond is seen from both ends: a quarter of k |u|^2 per end.
    return 0.25 * bond_energy + 0.5 * p.lambda[i] * volume_ * p.strain[i] * p.strain[i];
  }

  // A bond turned inside out: r_ij . R(theta_ij) r0_ij <= 0. Reports the bond
  // with the smallest cosine between r_ij and R(theta_ij) r0_ij.
  IntegrityReport check_integrity(const ParticleStore& p, const BondTable& bonds,
                                  const IntegrityLimits&) const {
    std::vector<double> worst(p.size());
    std::vector<std::size_t> partner(p.size());
    parallel_for(0, p.size(), [&](std::size_t i) {
      double lowest = 1.0;
      std::size_t at = i;
      for_each_bond(
          p, bonds, i, [&](std::uint32_t b, std::size_t j, const auto& v, double inv_len) {
            const double ax = v.rx - v.ux, ay = v.ry - v.uy;  // R(theta_ij) r0_ij
            const double cosine =
                (v.rx * ax + v.ry * ay) * inv_len / std::hypot(bonds.r0x[b], bonds.r0y[b]);
            if (cosine < lowest) {
              lowest = cosine;
              at = j;
            }
          });
      worst[i] = lowest;
      partner[i] = at;
    });
    IntegrityReport r;
    if (p.size() == 0) return r;
    r.particle = index_of_min(worst);
    r.neighbor = partner[r.particle];
    r.value = worst[r.particle];
    r.failed = !(r.value > 0.0);
    r.criterion = "bond turned inside out (r_ij . R(theta_ij) r0_ij <= 0)";
    return r;
  }

  // (d / n0) w0_ij / |r0_ij| and k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (N/m) per bond entry.
  const std::vector<double>& strain_coefficients() const { return strain_coef_; }
  const std::vector<double>& spring_coefficients() const { return spring_coef_; }

 private:
  double volume_ = 0;
  std::vector<double> strain_coef_;
  std::vector<double> spring_coef_;
};

using PaperModel = PaperModelT<false>;
using PaperConservativeModel = PaperModelT<true>;

}  // namespace mpsolid
