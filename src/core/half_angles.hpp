#pragma once
// Half angles c_i = cos(theta_i / 2), s_i = sin(theta_i / 2): one sin and cos
// per particle per step (a polynomial, vectorised with the integration), so
// no bond needs a trigonometric call.
#include <cmath>

#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

struct HalfAngle {
  double cos, sin;
};

// sin and cos of x by polynomials, branch-free so that a loop over particles
// vectorises (glibc's sincos is a call per particle, 5 ns each). x is
// reduced to r = x - k pi/2, |r| <= pi/4, with pi/2 in two parts (the first
// 33 bits, so k times it is exact for |k| < 2^20); r is x itself, exactly,
// for |x| <= pi/4, where every rotation of a solid lives. On r, fdlibm's
// kernels (__kernel_sin, __kernel_cos: minimax polynomials, error below
// 1 ulp); the quadrant k mod 4 picks and signs them. Accuracy against
// glibc: tests/unit/test_half_angles.cpp. sin(0) = 0 and cos(0) = 1 exactly
// (walls rely on it).
struct SinCos {
  double sin, cos;
};
inline SinCos sin_cos(double x) {
  constexpr double kTwoOverPi = 6.36619772367581382433e-01;
  constexpr double kPio2Hi = 1.57079632673412561417e+00;  // pi/2, first 33 bits
  constexpr double kPio2Lo = 6.07710050650619224932e-11;  // pi/2 - kPio2Hi
  constexpr double kRound = 6755399441055744.0;           // 1.5 * 2^52: round to nearest
  const double k = (x * kTwoOverPi + kRound) - kRound;
  const double r = (x - k * kPio2Hi) - k * kPio2Lo;
  const double z = r * r;
  // __kernel_sin(r, 0, 0)
  constexpr double S1 = -1.66666666666666324348e-01, S2 = 8.33333333332248946124e-03,
                   S3 = -1.98412698298579493134e-04, S4 = 2.75573137070700676789e-06,
                   S5 = -2.50507602534068634195e-08, S6 = 1.58969099521155010221e-10;
  const double v = z * r;
  const double sr = r + v * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
  // __kernel_cos(r, 0)
  constexpr double C1 = 4.16666666666666019037e-02, C2 = -1.38888888888741095749e-03,
                   C3 = 2.48015872894767294178e-05, C4 = -2.75573143513906633035e-07,
                   C5 = 2.08757232129817482790e-09, C6 = -1.13596475577881948265e-11;
  const double hz = 0.5 * z;
  const double w = 1.0 - hz;
  const double cr =
      w + (((1.0 - w) - hz) + z * (z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))))));
  // Quadrant: (sin, cos) = (s, c), (c, -s), (-s, -c), (-c, s).
  const auto quadrant = static_cast<long long>(k) & 3;
  const double sin_abs = (quadrant & 1) ? cr : sr;
  const double cos_abs = (quadrant & 1) ? sr : cr;
  return {(quadrant & 2) ? -sin_abs : sin_abs, ((quadrant + 1) & 2) ? -cos_abs : cos_abs};
}

// The one formula every writer of half_cos/half_sin uses (the pass below, the
// integration and the rigid-body placement), so they give the same bits.
inline HalfAngle half_angle(double theta) {
  const SinCos h = sin_cos(0.5 * theta);
  return {h.cos, h.sin};
}

inline void set_half_angle(ParticleStore& p, std::size_t i) {
  const HalfAngle h = half_angle(p.theta[i]);
  p.half_cos[i] = h.cos;
  p.half_sin[i] = h.sin;
}

// (In space an orientation is a quaternion: nothing to compute.)
inline void compute_half_angles(ParticleStore& p, Range range) {
  if (p.dimension == 3) return;
  parallel_for(range.begin, range.end, [&](std::size_t i) { set_half_angle(p, i); });
}

}  // namespace mpsolid
