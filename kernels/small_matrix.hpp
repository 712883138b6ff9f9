#pragma once
// Small row-major Dim x Dim matrices (Dim 2 or 3) of one particle (T double)
// or of kLanes particles side by side (T Lanes, kernels/lanes.hpp), with the
// same operations lane by lane: the corrected-gradient kernels' per-particle
// algebra (kernels/gradient_gather_model.hpp) and the laws' stresses
// (kernels/finite_strain_model.hpp, kernels/linear_elastic_model.hpp).
#include <array>
#include <type_traits>

namespace mpsolid {

// Row-major Dim x Dim products and determinants of one particle's matrix
// (T double) or kLanes particles' (T Lanes).
template <int Dim, class T>
using SmallMatrix = std::array<T, Dim * Dim>;

template <int Dim, class T>
SmallMatrix<Dim, T> matrix_product(const SmallMatrix<Dim, T>& a, const SmallMatrix<Dim, T>& b) {
  SmallMatrix<Dim, T> c;
  for (int r = 0; r < Dim; ++r)
    for (int k = 0; k < Dim; ++k) {
      T sum = a[r * Dim] * b[k];
      for (int m = 1; m < Dim; ++m) sum += a[r * Dim + m] * b[m * Dim + k];
      c[r * Dim + k] = sum;
    }
  return c;
}

template <int Dim, class T>
T determinant(const SmallMatrix<Dim, T>& f) {
  if constexpr (Dim == 2)
    return f[0] * f[3] - f[1] * f[2];
  else
    return f[0] * (f[4] * f[8] - f[5] * f[7]) - f[1] * (f[3] * f[8] - f[5] * f[6]) +
           f[2] * (f[3] * f[7] - f[4] * f[6]);
}

// The cofactor matrix (det F F^-T).
template <int Dim, class T>
SmallMatrix<Dim, T> cofactors(const SmallMatrix<Dim, T>& f) {
  if constexpr (Dim == 2)
    return {f[3], -f[2], -f[1], f[0]};
  else
    return {f[4] * f[8] - f[5] * f[7], f[5] * f[6] - f[3] * f[8], f[3] * f[7] - f[4] * f[6],
            f[2] * f[7] - f[1] * f[8], f[0] * f[8] - f[2] * f[6], f[1] * f[6] - f[0] * f[7],
            f[1] * f[5] - f[2] * f[4], f[2] * f[3] - f[0] * f[5], f[0] * f[4] - f[1] * f[3]};
}

// T from a double (broadcast to every lane) or from T itself.
template <class T, class V>
T broadcast(V v) {
  if constexpr (std::is_same_v<T, V>)
    return v;
  else
    return T{} + v;
}

}  // namespace mpsolid
