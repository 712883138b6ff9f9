#pragma once
// The one bond predicate every search shares: |r_j - r_i|^2 < re^2, computed
// in the same operation order, so cell list, k-d tree and brute force agree
// bit for bit on borderline pairs.

namespace mpsolid {

inline double squared_distance(double xi, double yi, double xj, double yj) {
  const double dx = xj - xi;
  const double dy = yj - yi;
  return dx * dx + dy * dy;
}

inline bool within_radius(double xi, double yi, double xj, double yj, double re_squared) {
  return squared_distance(xi, yi, xj, yj) < re_squared;
}

}  // namespace mpsolid
