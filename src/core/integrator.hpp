#pragma once
// Symplectic Euler (the paper's Eq. 8-9): the new velocity moves the position.
// Serial over the range: the step calls these on each thread's block.
#include "src/core/particle_store.hpp"

namespace mpsolid {

// v += dt f / m, r += dt v; with rotation also omega += dt tau / I,
// theta += dt omega and the new half angles (so the next step needs no
// separate half-angle pass); in space the orientation quaternion turned by
// omega dt instead.
void kick_drift(ParticleStore& p, Range range, double dt, bool with_rotation);

// Velocity update only (rigid particles: their pose update places them).
void kick(ParticleStore& p, Range range, double dt, bool with_rotation);

}  // namespace mpsolid
