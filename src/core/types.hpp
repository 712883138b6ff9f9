#pragma once
// Basic types shared by the whole solver.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace mpsolid {

// The plane's dimension, which the plane kernels use (plane strain, MODEL.md
// section 1; in space the kernels take the store's dimension, 3).
inline constexpr int kDim = 2;

// The z component of a x b for in-plane vectors (torques, angular momenta).
// T: double, or a vector of lanes (kernels/bond_slots.hpp) computing it lane-wise.
template <class T>
inline T cross(T ax, T ay, T bx, T by) {
  return ax * by - ay * bx;
}

// Kind of a particle. Storage is grouped in this order: [wall | elastic | rigid].
enum class Kind : std::int8_t { wall = 0, elastic = 1, rigid = 2 };

const char* kind_name(Kind kind);

// The number an element travels as (in rank messages, numpy arrays): an
// enumeration's underlying integer, any other type itself.
template <class T>
struct NumberOf {
  using type = T;
};
template <class T>
requires std::is_enum_v<T>
struct NumberOf<T> {
  using type = std::underlying_type_t<T>;
};
template <class T>
using NumberOf_t = typename NumberOf<T>::type;

// Half-open index range [begin, end) into the particle store.
struct Range {
  std::size_t begin = 0;
  std::size_t end = 0;
  std::size_t size() const { return end - begin; }
  bool empty() const { return end == begin; }
};

// Bad user input (case file, command line): reported with exit code 2.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace mpsolid
