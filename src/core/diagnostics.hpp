#pragma once
// Whole-system figures at a frame: energies (MODEL.md section 4b), momenta
// (about the origin, spins included) and the largest speed.
#include "src/core/solver_state.hpp"

namespace mpsolid {

struct Diagnostics {
  double kinetic_energy = 0;  // translational + rotational
  double strain_energy = 0;
  double contact_energy = 0;  // 0 without contact
  // The smallest distance between two contact candidates that may touch,
  // capped at the search's reach (0 without contact).
  double contact_min_distance = 0;
  double external_work = 0;
  double damping_loss = 0;  // the energy damping took out (0 without [damping])
  double momentum_x = 0, momentum_y = 0;
  double angular_momentum = 0;
  double max_speed = 0;
};

// Kinetic energy, momenta and max speed of the moving particles.
Diagnostics motion_diagnostics(const ParticleStore& p);

// Everything, with the model's strain energy already summed (in the ordered
// sums' chunk order, on one rank or from the ranks' chunk sums).
Diagnostics diagnostics_with_strain_energy(const SolverState& s, double strain_energy);

}  // namespace mpsolid
