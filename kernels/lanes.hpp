#pragma once
// Eight values side by side, in GCC's vector extension: the gathers keep
// eight particles' sums in registers across all their bonds
// (kernels/bond_slots.hpp, gather_lanes). GCC lowers it to the target's
// vectors (one AVX-512 register, two AVX2 or four SSE2 ones). Lane-wise +,
// -, * and / are the scalar IEEE operations, so each lane gives the bits of
// the scalar code; functions without a vector form (lane_log) call the
// scalar one lane by lane.
#include <cmath>
#include <cstddef>
#include <cstring>

namespace mpsolid {

inline constexpr std::size_t kLanes = 8;
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

inline Lanes load_lanes(const double* from) {
  Lanes v;
  std::memcpy(&v, from, sizeof v);
  return v;
}
inline void store_lanes(double* to, Lanes v) {
  std::memcpy(to, &v, sizeof v);
}

// One value or kLanes consecutive ones, as T (double or Lanes), and back:
// a kernel written once for both.
template <class T>
inline T load_as(const double* from) {
  if constexpr (sizeof(T) == sizeof(double))
    return *from;
  else
    return load_lanes(from);
}
inline void store_to(double* to, double v) {
  *to = v;
}
inline void store_to(double* to, Lanes v) {
  store_lanes(to, v);
}

// Component c of kLanes rows of `width` values from `rows` (a row-major
// array of small tensors), and back.
inline Lanes load_strided(const double* rows, std::size_t width, std::size_t c) {
  Lanes v;
  for (std::size_t k = 0; k < kLanes; ++k) v[k] = rows[k * width + c];
  return v;
}
inline void store_strided(double* rows, std::size_t width, std::size_t c, Lanes v) {
  for (std::size_t k = 0; k < kLanes; ++k) rows[k * width + c] = v[k];
}

// Slot data larger than this comes from memory, where a gather's hundred
// or so streams (a dozen entries times its fields) are more than the
// hardware prefetchers follow: its gathers then prefetch each stream a few
// groups ahead. Smaller data stays in the caches, where prefetches only cost.
inline constexpr std::size_t kPrefetchAboveBytes = std::size_t{24} << 20;
inline constexpr std::size_t kPrefetchAhead = 8 * kLanes;  // values ahead
template <bool Prefetch>
inline Lanes load_lanes_ahead(const double* from) {
  if constexpr (Prefetch) __builtin_prefetch(from + kPrefetchAhead);
  return load_lanes(from);
}

// The square root of a value, or of each lane (correctly rounded either way).
inline double lane_sqrt(double x) {
  return std::sqrt(x);
}
inline Lanes lane_sqrt(Lanes v) {
  for (std::size_t k = 0; k < kLanes; ++k) v[k] = std::sqrt(v[k]);
  return v;
}

// -1 where a value is negative, else +1 (a value or each lane).
inline double lane_sign(double x) {
  return x < 0.0 ? -1.0 : 1.0;
}
inline Lanes lane_sign(Lanes v) {
  const Lanes one = Lanes{} + 1.0;
  return v < 0.0 ? -one : one;
}

// std::log of a value, or of each lane (glibc's: the scalar bits).
inline double lane_log(double x) {
  return std::log(x);
}
inline Lanes lane_log(Lanes v) {
  for (std::size_t k = 0; k < kLanes; ++k) v[k] = std::log(v[k]);
  return v;
}

}  // namespace mpsolid
