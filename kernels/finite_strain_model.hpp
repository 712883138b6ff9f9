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
#include <Eigen/Dense>
#include <cmath>

#include "kernels/corrected_gradient_model.hpp"
#include "kernels/small_matrix.hpp"

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

  // The same law on a row-major Dim x Dim array (kernels/gradient_gather_model.hpp),
  // with W = mu/2 (F:F - Dim) - mu ln J + lambda/2 (ln J)^2.
  template <int Dim, class T>
  static void piola(const T* f, T jac, T lambda, T mu, T* out, T& strain, T& pressure) {
    if constexpr (Dim == 2) {
      piola(f, jac, lambda, mu, out, strain, pressure);
    } else {
      const T log_j = lane_log(jac);
      SmallMatrix<3, T> m;
      for (int k = 0; k < 9; ++k) m[k] = f[k];
      const SmallMatrix<3, T> cof = cofactors<3>(m);  // J F^-T
      for (int k = 0; k < 9; ++k) {
        const T fit = cof[k] / jac;
        out[k] = mu * (f[k] - fit) + lambda * log_j * fit;
      }
      strain = log_j;
      pressure = -lambda * log_j / jac;
    }
  }

  // W in H = F - I, as above: J - 1 = tr H + I2(H) + det H (I2 the sum of
  // the principal 2 x 2 minors), and (F:F - Dim) / 2 - ln J = H:H / 2 - I2(H)
  // - det H + (d - ln(1 + d)), with H:H / 2 - I2(H) = sum over a < b of
  // ((h_ab + h_ba)^2 + (h_aa - h_bb)^2) / 2, less sum_a h_aa^2 / 2 in space:
  // every term of the order of H^2 or H^3, computed from H.
  template <int Dim>
  static double energy_density(const Eigen::Matrix<double, Dim, Dim>& f, double lambda, double mu) {
    const Eigen::Matrix<double, Dim, Dim> h = f - Eigen::Matrix<double, Dim, Dim>::Identity();
    double minors = 0, quadratic = 0;
    for (int a = 0; a < Dim; ++a)
      for (int b = a + 1; b < Dim; ++b) {
        minors += h(a, a) * h(b, b) - h(a, b) * h(b, a);
        const double sum = h(a, b) + h(b, a), difference = h(a, a) - h(b, b);
        quadratic += 0.5 * (sum * sum + difference * difference);
      }
    double cubic = 0;
    if constexpr (Dim == 3) {
      quadratic -= 0.5 * (h(0, 0) * h(0, 0) + h(1, 1) * h(1, 1) + h(2, 2) * h(2, 2));
      cubic = h.determinant();
    }
    const double d = h.trace() + minors + cubic;
    const double log_j = std::log1p(d);
    const double excess =
        std::abs(d) < 1e-3 ? d * d * (0.5 - d * (1.0 / 3 - d * (0.25 - d * 0.2))) : d - log_j;
    return mu * (quadratic - cubic + excess) + 0.5 * lambda * log_j * log_j;
  }
};

using FiniteStrainModel = CorrectedGradientModel<NeoHookeanLaw>;

}  // namespace mpsolid
