#pragma once
// Slow, obviously correct versions of the paper model's kernels, written
// straight from the paper's Eq. 3-7 in acceleration form: a pair loop
// (each bond once, i < j) that scatters to both ends, with trigonometric calls
// per bond and explicit normal/shear split. Test oracles only.
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

struct FiniteStrainResult {
  std::vector<double> def_grad;  // row-major 2x2 per particle
  std::vector<double> jacobian;
  std::vector<double> fx, fy;
};

// MODEL.md section 5 with Eigen matrices and a pair loop that scatters each
// bond's force to both ends; `consistent` adds the hourglass energy's
// dependence on F (see kernels/finite_strain_model.hpp).
FiniteStrainResult finite_strain_model(const ParticleStore& p, const BondTable& bonds,
                                       double hourglass, bool consistent);

}  // namespace mpsolid::reference
