#pragma once
// Half angles c_i = cos(theta_i / 2), s_i = sin(theta_i / 2): one sincos per
// particle per step, so no bond needs a trigonometric call.
#include <cmath>

#include "src/parallel.hpp"
#include "src/particle_store.hpp"

namespace mpsolid {

inline void compute_half_angles(ParticleStore& p, Range range) {
  parallel_for(range.begin, range.end, [&](std::size_t i) {
    p.half_cos[i] = std::cos(0.5 * p.theta[i]);
    p.half_sin[i] = std::sin(0.5 * p.theta[i]);
  });
}

}  // namespace mpsolid
