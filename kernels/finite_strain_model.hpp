#pragma once
// The finite-strain model (MODEL.md section 5): a compressible neo-Hookean
// law on the kernel-corrected deformation gradient, with the hourglass
// penalty (kernels/corrected_gradient_model.hpp).
//
//   P = mu (F - F^-T) + lambda ln(J) F^-T   (plane-strain first Piola-Kirchhoff)
//   W = mu/2 (F:F - 2) - mu ln J + lambda/2 (ln J)^2,   P = dW/dF
//
// W depends on F only through F^T F, so the energy is rotation invariant and
// angular momentum is conserved to round-off. Outputs: strain = ln J
// (volumetric), pressure = -lambda ln(J) / J. Options in [finite_strain].
#include <cmath>

#include "kernels/corrected_gradient_model.hpp"

namespace mpsolid {

struct NeoHookeanLaw {
  static constexpr const char* name = "finite_strain";
  static constexpr bool rotation_invariant = true;

  // T: double, or Lanes (eight particles, lane by lane).
  template <class T>
  static void piola(const T* f, T jac, T lambda, T mu, T* out, T& strain, T& pressure) {
    const T log_j = lane_log(jac);
    // F^-T = (1 / J) [[f3, -f2], [-f1, f0]]
    const T fit[4] = {f[3] / jac, -f[2] / jac, -f[1] / jac, f[0] / jac};
    for (int k = 0; k < 4; ++k) out[k] = mu * (f[k] - fit[k]) + lambda * log_j * fit[k];
    strain = log_j;
    pressure = -lambda * log_j / jac;
  }

  static double energy_density(const double* f, double jac, double lambda, double mu) {
    const double log_j = std::log(jac);
    const double frob = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] + f[3] * f[3];
    return 0.5 * mu * (frob - 2.0) - mu * log_j + 0.5 * lambda * log_j * log_j;
  }
};

using FiniteStrainModel = CorrectedGradientModel<NeoHookeanLaw>;

}  // namespace mpsolid
