#pragma once
// Slow, obviously correct versions of the paper model's kernels, written
// straight from the paper's Eq. 3-7 in acceleration form: a pair loop
// (each bond once, i < j) that scatters to both ends, with trigonometric calls
// per bond and explicit normal/shear split. Test oracles only.
#include <vector>

#include "src/bonds.hpp"
#include "src/particle_store.hpp"

namespace mpsolid::reference {

struct PaperResult {
  std::vector<double> strain, pressure;  // every particle
  std::vector<double> fx, fy, torque;    // every particle (m a, I domega/dt)
};

PaperResult paper_model(const ParticleStore& p, const BondTable& bonds);

}  // namespace mpsolid::reference
