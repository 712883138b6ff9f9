#pragma once
// Slow, obviously correct versions of the paper model's kernels, written
// straight from the paper's Eq. 3-7 in acceleration form: a pair loop
// (each bond once, i < j) that scatters to both ends, with trigonometric calls
// per bond and explicit normal/shear split. Test oracles only.
#include <Eigen/Dense>
#include <functional>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid::reference {

struct PaperResult {
  std::vector<double> strain, pressure;  // every particle
  std::vector<double> fx, fy, torque;    // every particle (m a, I domega/dt)
};

// energy_consistent adds MODEL.md 4b's terms: with
// C = (m / rho)(d / n0) w0 (p_i + p_j) / (|r0| |r|), a force -C u^s_ij on i,
// +C u^s_ij on j and a torque (1/2) C |r_ij| (u_ij x e_ij) on both.
PaperResult paper_model(const ParticleStore& p, const BondTable& bonds,
                        bool energy_consistent = false);

// A material law on the corrected gradient, in Eigen: P(F) and W(F).
struct GradientLaw {
  std::function<Eigen::Matrix2d(const Eigen::Matrix2d& f, double lambda, double mu)> piola;
  std::function<double(const Eigen::Matrix2d& f, double lambda, double mu)> energy_density;
};
GradientLaw neo_hookean_law();  // MODEL.md section 5
GradientLaw hooke_law();        // MODEL.md section 7

struct GradientResult {
  std::vector<double> def_grad;        // row-major 2x2 per particle
  std::vector<double> jacobian;        // det F
  std::vector<Eigen::Matrix2d> piola;  // P(F_i)
  std::vector<double> fx, fy;
  double energy = 0;  // sum_i V W(F_i) + sum over bonds of 1/2 h_ij |g_ij|^2
};

// The corrected-gradient models (MODEL.md sections 5 and 7) with Eigen
// matrices and a pair loop that scatters each bond's force to both ends;
// `consistent` adds the hourglass energy's dependence on F.
GradientResult corrected_gradient_model(const ParticleStore& p, const BondTable& bonds,
                                        const GradientLaw& law, double hourglass, bool consistent);

inline GradientResult finite_strain_model(const ParticleStore& p, const BondTable& bonds,
                                          double hourglass, bool consistent) {
  return corrected_gradient_model(p, bonds, neo_hookean_law(), hourglass, consistent);
}

}  // namespace mpsolid::reference
