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

  // W written in H = F - I so that no term cancels: with d = J - 1 =
  // h0 + h3 + h0 h3 - h1 h2, (F:F - 2) / 2 - ln J = ((h0 - h3)^2 +
  // (h1 + h2)^2) / 2 + (d - ln(1 + d)), each part >= 0. The plain form loses
  // mu V 1e-16 per particle to round-off: 1e-10 J in a steel panel at rest,
  // which the energy balance of a body not yet loaded would read as a
  // blow-up.
  static double energy_density(const double* f, double, double lambda, double mu) {
    const double h0 = f[0] - 1.0, h1 = f[1], h2 = f[2], h3 = f[3] - 1.0;
    const double d = h0 + h3 + (h0 * h3 - h1 * h2);
    const double log_j = std::log1p(d);
    // d - ln(1 + d): its series where the difference would cancel.
    const double excess =
        std::abs(d) < 1e-3 ? d * d * (0.5 - d * (1.0 / 3 - d * (0.25 - d * 0.2))) : d - log_j;
    const double shear = 0.5 * ((h0 - h3) * (h0 - h3) + (h1 + h2) * (h1 + h2));
    return mu * (shear + excess) + 0.5 * lambda * log_j * log_j;
  }
};

using FiniteStrainModel = CorrectedGradientModel<NeoHookeanLaw>;

}  // namespace mpsolid
