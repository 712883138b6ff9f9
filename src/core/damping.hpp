#pragma once
// Mass-proportional damping over a window of steps (dynamic relaxation,
// MODEL.md section 2.16): a force -c m v on every moving particle (and
// -c I omega on its spin), taken at the step's mean velocity, so each
// velocity update is v+ = ((1 - c dt/2) v- + dt f/m) / (1 + c dt/2), stable
// for any c. Each particle keeps the energy its damping force took out of
// it (the state array damping_loss), so the energy balance closes with the
// loss counted, at any thread or rank count.
#include <cstdint>

#include "src/core/particle_store.hpp"

namespace mpsolid {

struct Damping {
  double coefficient = 0;       // c (1/s); 0: none
  std::int64_t first_step = 0;  // the window's steps, [first_step, end_step)
  std::int64_t end_step = 0;
  bool active(std::int64_t step) const {
    return coefficient > 0 && step >= first_step && step < end_step;
  }
};

// Replaces the forces and torques of the particles in `range` by the ones
// that give the damped update through the plain kick (f' = (f - c m v) /
// (1 + c dt/2)), and adds the damping's work over the step to each
// particle's damping_loss. Called after every other force, before the kick.
void damp_block(ParticleStore& p, Range range, double coefficient, double dt, bool with_rotation);

}  // namespace mpsolid
