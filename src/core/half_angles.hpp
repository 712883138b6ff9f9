#pragma once
// Half angles c_i = cos(theta_i / 2), s_i = sin(theta_i / 2): one sincos per
// particle per step, so no bond needs a trigonometric call.
#include <cmath>

#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

struct HalfAngle {
  double cos, sin;
};

// The one formula every writer of half_cos/half_sin uses (the pass below, the
// integration and the rigid-body placement), so they give the same bits.
inline HalfAngle half_angle(double theta) {
  return {std::cos(0.5 * theta), std::sin(0.5 * theta)};
}

inline void set_half_angle(ParticleStore& p, std::size_t i) {
  const HalfAngle h = half_angle(p.theta[i]);
  p.half_cos[i] = h.cos;
  p.half_sin[i] = h.sin;
}

inline void compute_half_angles(ParticleStore& p, Range range) {
  parallel_for(range.begin, range.end, [&](std::size_t i) { set_half_angle(p, i); });
}

}  // namespace mpsolid
