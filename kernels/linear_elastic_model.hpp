#pragma once
// The linear-elastic model (MODEL.md section 7): small-strain Hooke's law on
// the kernel-corrected deformation gradient, with the hourglass penalty
// (kernels/corrected_gradient_model.hpp): what a linear finite-element code
// computes.
//
//   eps = (F + F^T) / 2 - I,   sigma = lambda tr(eps) I + 2 mu eps = P
//   W = lambda/2 (tr eps)^2 + mu eps : eps,   dW/dF = sigma (symmetric)
//
// Energy is conserved to O(dt) and linear momentum to round-off; W is not
// rotation invariant (a rigid rotation by a gives eps = (cos a - 1) I), so
// angular momentum is not conserved and large rotations are wrong. Outputs:
// strain = tr eps, pressure = -(lambda + mu) tr eps (minus the in-plane mean
// stress). Options in [linear_elastic].
#include <Eigen/Dense>

#include "kernels/corrected_gradient_model.hpp"

namespace mpsolid {

struct HookeLaw {
  static constexpr const char* name = "linear_elastic";
  static constexpr bool rotation_invariant = false;  // spurious strain ~ -a^2 / 2

  // T: double, or Lanes (eight particles, lane by lane).
  template <class T>
  static void piola(const T* f, T, T lambda, T mu, T* out, T& strain, T& pressure) {
    const T exx = f[0] - 1.0, eyy = f[3] - 1.0, exy = 0.5 * (f[1] + f[2]);
    const T volumetric = lambda * (exx + eyy);
    out[0] = volumetric + 2.0 * mu * exx;
    out[1] = 2.0 * mu * exy;
    out[2] = 2.0 * mu * exy;
    out[3] = volumetric + 2.0 * mu * eyy;
    const T trace = f[0] + f[3] - 2.0;  // tr eps
    strain = trace;
    pressure = -(lambda + mu) * trace;
  }

  static double energy_density(const double* f, double, double lambda, double mu) {
    const double exx = f[0] - 1.0, eyy = f[3] - 1.0, exy = 0.5 * (f[1] + f[2]);
    const double trace = exx + eyy;
    return 0.5 * lambda * trace * trace + mu * (exx * exx + eyy * eyy + 2.0 * exy * exy);
  }

  // The same law on a row-major Dim x Dim array (kernels/gradient_gather_model.hpp);
  // the pressure is minus the mean normal stress, -(lambda + 2 mu / Dim) tr eps.
  template <int Dim, class T>
  static void piola(const T* f, T jac, T lambda, T mu, T* out, T& strain, T& pressure) {
    if constexpr (Dim == 2) {
      piola(f, jac, lambda, mu, out, strain, pressure);
    } else {
      const T trace = (f[0] - 1.0) + (f[4] - 1.0) + (f[8] - 1.0);  // tr eps
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const T eps = r == c ? f[4 * r] - 1.0 : 0.5 * (f[3 * r + c] + f[3 * c + r]);
          out[3 * r + c] = r == c ? lambda * trace + 2.0 * mu * eps : 2.0 * mu * eps;
        }
      strain = trace;
      pressure = -(lambda + 2.0 * mu / 3.0) * trace;
    }
  }
  template <int Dim>
  static double energy_density(const Eigen::Matrix<double, Dim, Dim>& f, double lambda, double mu) {
    using M = Eigen::Matrix<double, Dim, Dim>;
    const M eps = 0.5 * (f + f.transpose()) - M::Identity();
    const double trace = eps.trace();
    return 0.5 * lambda * trace * trace + mu * eps.squaredNorm();
  }
};

using LinearElasticModel = CorrectedGradientModel<HookeLaw>;

}  // namespace mpsolid
