#pragma once
// The paper's elastic MPS model (MODEL.md section 2), as two gather passes.
//
// Pass 1, strain and pressure, for every particle (walls and rigid included):
//   eps_i = (d / n0) sum_j w0_ij (u_ij . e_ij) / |r0_ij|,   p_i = -lambda_i eps_i
// Pass 2, fused force and torque, for the moving particles:
//   f_i   = sum_j k_ij u_ij  -  V (d / n0) sum_j w0_ij (p_i + p_j) e_ij / |r0_ij|
//   tau_i = 1/2 sum_j k_ij (r_ij x u_ij)
// with k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (bond + shear stress of
// Eq. 5 fused: sigma^n + sigma^s = 2 mu u / |r0|), V = m / rho = l0^2 D, and
// p_ij = (p_i + p_j) / 2. The torque is the paper's -T_ij / 2 (Eq. 7): the
// normal part of u has no moment about r_ij, so r x u^s = r x u.
#include "kernels/bond_loop.hpp"
#include "src/bonds.hpp"
#include "src/parallel.hpp"
#include "src/particle_store.hpp"

namespace mpsolid {

struct PaperModel {
  static constexpr const char* name = "paper";
  static constexpr bool uses_rotation = true;

  static void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      double eps = 0.0;
      for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double inv_len) {
        eps += bonds.strain_coef[b] * bond_math::normal_extension(v, inv_len);
      });
      p.strain[i] = eps;
      p.pressure[i] = -p.lambda[i] * eps;
    });
  }

  static void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) {
    const double volume = bonds.constants.volume;
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      const double pi = p.pressure[i];
      double fx = 0.0, fy = 0.0, torque = 0.0;
      for_each_bond(
          p, bonds, i, [&](std::uint32_t b, std::size_t j, const auto& v, double inv_len) {
            const double k = bonds.spring_coef[b];
            const double push = volume * bonds.strain_coef[b] * (pi + p.pressure[j]) * inv_len;
            fx += k * v.ux - push * v.rx;
            fy += k * v.uy - push * v.ry;
            torque += k * bond_math::cross(v.rx, v.ry, v.ux, v.uy);
          });
      p.fx[i] = fx;
      p.fy[i] = fy;
      p.torque[i] = 0.5 * torque;
    });
  }

  // Strain energy of particle i (MODEL.md section 4b): its share of
  // sum over bonds (each once) of 1/2 k_ij |u_ij|^2, plus 1/2 lambda_i V eps_i^2.
  // Needs the strain pass at the current state.
  static double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                       std::size_t i) {
    double bond_energy = 0.0;
    for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double) {
      bond_energy += bonds.spring_coef[b] * (v.ux * v.ux + v.uy * v.uy);
    });
    // Each bond is seen from both ends: a quarter of k |u|^2 per end.
    return 0.25 * bond_energy +
           0.5 * p.lambda[i] * bonds.constants.volume * p.strain[i] * p.strain[i];
  }
};

}  // namespace mpsolid
