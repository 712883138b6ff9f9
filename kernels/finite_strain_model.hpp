#pragma once
// The finite-strain model (MODEL.md section 5): a total-Lagrangian,
// kernel-corrected deformation gradient per particle, a compressible
// neo-Hookean law and an hourglass penalty. No rotation degree of freedom:
// F carries the rotation, so the step skips half angles and spins.
//
// Set-up, per particle:  A_i = sum_j wl_ij r0_ij (x) r0_ij,   wl_ij = w0_ij / |r0_ij|^2
// Pass 1 (all particles): F_i = (sum_j wl_ij r_ij (x) r0_ij) A_i^-1,  J_i = det F_i,
//   P_i = mu (F_i - F_i^-T) + lambda ln(J_i) F_i^-T   (plane-strain first Piola-Kirchhoff)
// Pass 2 (moving particles):
//   f_i = sum_j [ wl_ij V (P_i A_i^-1 + P_j A_j^-1) r0_ij
//               + alpha E_ij V (2 / n0) wl_ij (r_ij - (F_i + F_j) r0_ij / 2) ]
// The first sum is exactly -d/dr_i of sum_i V W(F_i) with
//   W = mu/2 (F:F - 2) - mu ln J + lambda/2 (ln J)^2.
// Outputs: strain = ln J (volumetric), pressure = -lambda ln(J) / J.
#include <vector>

#include "kernels/model_common.hpp"
#include "src/bonds.hpp"
#include "src/particle_store.hpp"

namespace mpsolid {

class FiniteStrainModel {
 public:
  static constexpr const char* name = "finite_strain";
  static constexpr bool uses_rotation = false;

  // Throws InputError if a particle's neighbourhood cannot define A_i^-1.
  FiniteStrainModel(const ParticleStore& p, const BondTable& bonds, const ModelOptions& options);

  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range);
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const;
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const;
  // J_i at or below the minimum (needs the strain pass at the current state).
  IntegrityReport check_integrity(const ParticleStore& p, const BondTable& bonds) const;

  // Row-major 2x2 tensors per particle, from the last strain pass.
  const std::vector<double>& deformation_gradient() const { return def_grad_; }
  const std::vector<double>& jacobian() const { return jacobian_; }

 private:
  double min_jacobian_;
  std::vector<double> a_inv_;      // A_i^-1, 4 per particle
  std::vector<double> def_grad_;   // F_i, 4 per particle
  std::vector<double> stress_a_;   // P_i A_i^-1, 4 per particle
  std::vector<double> jacobian_;   // J_i
  std::vector<double> wl_volume_;  // V wl_ij per bond entry
  std::vector<double> hourglass_;  // alpha E_ij V (2 / n0) wl_ij per bond entry
};

}  // namespace mpsolid
