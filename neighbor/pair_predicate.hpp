#pragma once
// The one bond predicate every search shares: |r_j - r_i|^2 < re^2, computed
// in the same operation order, so cell list, k-d tree and brute force agree
// bit for bit on borderline pairs.
#include <cstddef>

#include "neighbor/neighbor_lists.hpp"

namespace mpsolid {

inline double squared_distance(double xi, double yi, double xj, double yj) {
  const double dx = xj - xi;
  const double dy = yj - yi;
  return dx * dx + dy * dy;
}

inline bool within_radius(double xi, double yi, double xj, double yj, double re_squared) {
  return squared_distance(xi, yi, xj, yj) < re_squared;
}

// Points i and j of a cloud of dimension Dim (the plane's sum, then dz^2).
template <int Dim>
inline bool within_radius(const PointCloud& p, std::size_t i, std::size_t j, double re_squared) {
  double d2 = squared_distance(p.x[i], p.y[i], p.x[j], p.y[j]);
  if constexpr (Dim == 3) {
    const double dz = p.z[j] - p.z[i];
    d2 += dz * dz;
  }
  return d2 < re_squared;
}

// The cloud's coordinate array along axis a (0 x, 1 y, 2 z).
inline std::span<const double> axis(const PointCloud& p, int a) {
  return a == 0 ? p.x : a == 1 ? p.y : p.z;
}

// Calls f.template operator()<Dim>() with the cloud's dimension.
template <class F>
decltype(auto) with_dimension(const PointCloud& p, F&& f) {
  if (p.in_space()) return f.template operator()<3>();
  return f.template operator()<2>();
}

}  // namespace mpsolid
