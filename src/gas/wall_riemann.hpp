#pragma once
// The pressure on a wall that moves into or away from a gas: the exact
// solution of the half Riemann problem between the gas (density rho,
// pressure p, velocity un along the wall's normal, counted toward the wall)
// and the wall's normal velocity wall_un (the same sense). The gas meets the
// wall through a shock when it approaches it faster than the wall recedes,
// through a rarefaction otherwise (zero pressure: a vacuum opens).
#include <cmath>

namespace mpsolid {

inline double wall_pressure(double rho, double un, double p, double gamma, double wall_un) {
  const double approach = un - wall_un;
  if (approach > 0) {
    // Shock: approach = (p* - p) sqrt(a / (p* + b)), a quadratic in p* - p.
    const double a = 2 / ((gamma + 1) * rho), b = (gamma - 1) / (gamma + 1) * p;
    const double u2 = approach * approach;
    return p + (u2 + std::sqrt(u2 * u2 + 4 * a * u2 * (p + b))) / (2 * a);
  }
  const double c = std::sqrt(gamma * p / rho);
  const double base = 1 + 0.5 * (gamma - 1) * approach / c;
  return base > 0 ? p * std::pow(base, 2 * gamma / (gamma - 1)) : 0.0;
}

// How fast the wave that the wall sends into the gas (same arguments)
// travels away from the wall: the shock's speed when the gas meets the wall
// through a shock (faster than |un| + c when the wall is pushed in hard),
// the rarefaction's head otherwise.
inline double wall_wave_speed(double rho, double un, double p, double gamma, double wall_un) {
  const double approach = un - wall_un, c = std::sqrt(gamma * p / rho);
  if (approach <= 0) return std::abs(c - un);
  const double half = 0.25 * (gamma + 1) * approach;
  return std::abs(half + std::sqrt(half * half + c * c) - un);
}

}  // namespace mpsolid
