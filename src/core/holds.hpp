#pragma once
// Velocity components held at zero (frictionless rollers): the held force
// components are cleared after the force pass and loads, so a particle that
// starts at rest in that direction never moves in it.
#include <vector>

#include "src/core/particle_store.hpp"

namespace mpsolid {

struct HeldRange {
  Range range;
  bool x = false, y = false, z = false;  // z only in space
};

// Clears the held components of the particles of `block` (serially: it is
// called per thread block, after that block's loads).
void clear_held_forces(ParticleStore& p, const std::vector<HeldRange>& holds, Range block);

}  // namespace mpsolid
