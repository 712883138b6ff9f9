#pragma once
// Structure-of-arrays particle store. Particles are grouped by kind in storage
// order [wall | elastic | rigid body 0 | rigid body 1 | ...] so hot loops run
// over index ranges. Stable ids (creation order) are separate from storage
// order; outputs are written in id order.
//
// Every per-particle array is one line of MPSOLID_PARTICLE_ARRAYS below; the
// store's members, resize, the state copies (snapshots, checkpoints, the
// slices that move between ranks), a rank's part and the Python views are
// all derived from it. Adding an array is adding its line.
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "src/core/types.hpp"

namespace mpsolid {

// What an array is to the solver, which decides where it goes.
enum class ArrayRole : std::int8_t {
  state,      // evolves in time: snapshots, checkpoints and the ranks' slices copy it
  reference,  // the set-up configuration
  work,       // recomputed from the state every step
  constant,   // fixed at set-up
};

const char* role_name(ArrayRole role);

// The stores an array is in: every store, only a 2D one, or only a 3D one
// (an orientation is an angle in the plane, a quaternion in space).
enum class ArrayDims : std::int8_t { any, plane, space };

inline constexpr bool present_in(ArrayDims dims, int dimension) {
  return dims == ArrayDims::any || (dims == ArrayDims::plane) == (dimension == 2);
}

// The table: member, the name files and Python know it by, element type,
// role, the dimensions it exists in, the value resize gives it, and what it
// holds. Kept in the order checkpoints list the state arrays; a store of one
// dimension holds the rows of that dimension, in this order.
// clang-format off
#define MPSOLID_PARTICLE_ARRAYS(X)                                                              \
  X(x,           "x",           double,       state,     any,   0.0,           "position x (m)")          \
  X(y,           "y",           double,       state,     any,   0.0,           "position y (m)")          \
  X(z,           "z",           double,       state,     space, 0.0,           "position z (m)")          \
  X(vx,          "vx",          double,       state,     any,   0.0,           "velocity x (m/s)")        \
  X(vy,          "vy",          double,       state,     any,   0.0,           "velocity y (m/s)")        \
  X(vz,          "vz",          double,       state,     space, 0.0,           "velocity z (m/s)")        \
  X(theta,       "theta",       double,       state,     plane, 0.0,           "rotation angle (rad)")    \
  X(qw,          "qw",          double,       state,     space, 1.0,           "orientation quaternion w") \
  X(qx,          "qx",          double,       state,     space, 0.0,           "orientation quaternion x") \
  X(qy,          "qy",          double,       state,     space, 0.0,           "orientation quaternion y") \
  X(qz,          "qz",          double,       state,     space, 0.0,           "orientation quaternion z") \
  X(omega_x,     "omega_x",     double,       state,     space, 0.0,           "angular velocity x (rad/s)") \
  X(omega_y,     "omega_y",     double,       state,     space, 0.0,           "angular velocity y (rad/s)") \
  X(omega,       "omega",       double,       state,     any,   0.0,           "angular velocity (about z in space; rad/s)") \
  X(damping_loss, "damping_loss", double,     state,     any,   0.0,           "energy damping took out (J)") \
  X(x0,          "x0",          double,       reference, any,   0.0,           "reference position x (m)") \
  X(y0,          "y0",          double,       reference, any,   0.0,           "reference position y (m)") \
  X(z0,          "z0",          double,       reference, space, 0.0,           "reference position z (m)") \
  X(half_cos,    "half_cos",    double,       work,      plane, 1.0,           "cos(theta/2)")            \
  X(half_sin,    "half_sin",    double,       work,      plane, 0.0,           "sin(theta/2)")            \
  X(strain,      "strain",      double,       work,      any,   0.0,           "volumetric strain")       \
  X(pressure,    "pressure",    double,       work,      any,   0.0,           "pressure (Pa)")           \
  X(fx,          "fx",          double,       work,      any,   0.0,           "force x (N; in 2D over the depth)") \
  X(fy,          "fy",          double,       work,      any,   0.0,           "force y (N; in 2D over the depth)") \
  X(fz,          "fz",          double,       work,      space, 0.0,           "force z (N)")             \
  X(torque_x,    "torque_x",    double,       work,      space, 0.0,           "torque x (N m)")          \
  X(torque_y,    "torque_y",    double,       work,      space, 0.0,           "torque y (N m)")          \
  X(torque,      "torque",      double,       work,      any,   0.0,           "torque (about z in space; N m)") \
  X(inv_mass,    "inv_mass",    double,       constant,  any,   0.0,           "1 / mass (1/kg)")         \
  X(inv_inertia, "inv_inertia", double,       constant,  any,   0.0,           "1 / moment of inertia (1/(kg m^2))") \
  X(lambda,      "lambda",      double,       constant,  any,   0.0,           "Lame lambda of the material (Pa)") \
  X(mu,          "mu",          double,       constant,  any,   0.0,           "Lame mu of the material (Pa)") \
  X(id,          "ids",         std::int32_t, constant,  any,   0,             "stable id (creation order)") \
  X(body,        "bodies",      std::int32_t, constant,  any,   0,             "body index (case order)") \
  X(material,    "materials",   std::int32_t, constant,  any,   0,             "material index")          \
  X(kind,        "kinds",       Kind,         constant,  any,   Kind::elastic, "kind as its integer (KIND_NAMES names it)")
// clang-format on

struct ParticleStore {
  // 2 (plane strain) or 3; set before resize. An array of the other
  // dimension only (z in 2D, theta in 3D) stays empty.
  int dimension = 2;
#define MPSOLID_DECLARE_ARRAY(member, name, type, role, dims, initial, what) \
  std::vector<type> member;
  MPSOLID_PARTICLE_ARRAYS(MPSOLID_DECLARE_ARRAY)
#undef MPSOLID_DECLARE_ARRAY

  // Storage ranges by kind.
  Range walls, elastic, rigid;

  std::size_t size() const {
    return x.size();
  }
  // Particles whose motion is integrated (elastic and rigid).
  Range moving() const {
    return {elastic.begin, rigid.end};
  }
  Range all() const {
    return {0, size()};
  }

  // Every array n values of its initial value.
  void resize(std::size_t n);
  // The kind ranges (walls, elastic, rigid) from the kinds of [0, end),
  // which must be grouped in storage; an empty group sits at its
  // neighbours' boundary. (A rank's part in pieces holds its other ghosts
  // after `end`, in no kind range.)
  void set_kind_ranges() {
    set_kind_ranges(size());
  }
  void set_kind_ranges(std::size_t end);
  // Storage index of each id (inverse of `id`).
  std::vector<std::size_t> storage_of_id() const;
};

// One row of the table, as data.
template <class T>
struct ParticleArrayInfo {
  using value_type = T;
  const char* name;
  ArrayRole role;
  ArrayDims dims;
  T initial;
  const char* what;
  bool present_in(int dimension) const { return mpsolid::present_in(dims, dimension); }
};

// Calls f(ParticleArrayInfo<T>, std::vector<T> ParticleStore::*) for every
// row of the table, in order, both dimensions' rows (info.present_in says
// whether a store holds it).
template <class F>
constexpr void for_each_particle_member(F&& f) {
#define MPSOLID_VISIT_ARRAY(member, name, type, role, dims, initial, what)          \
  f(ParticleArrayInfo<type>{name, ArrayRole::role, ArrayDims::dims, initial, what}, \
    &ParticleStore::member);
  MPSOLID_PARTICLE_ARRAYS(MPSOLID_VISIT_ARRAY)
#undef MPSOLID_VISIT_ARRAY
}

// Calls f(ParticleArrayInfo<T>, array) for every array `p` (const or not)
// holds in its dimension, in the table's order.
template <class Store, class F>
void for_each_particle_array(Store& p, F&& f) {
  for_each_particle_member([&](const auto& info, auto member) {
    if (info.present_in(p.dimension)) f(info, p.*member);
  });
}

// The arrays of the state role (all of them double), by name: what
// snapshots, checkpoints and the ranks' slices copy.
struct StateArray {
  const char* name;
  std::vector<double> ParticleStore::*member;
  ArrayDims dims;
};
namespace detail {
template <class T>
inline constexpr bool holds_doubles = std::is_same_v<typename T::value_type, double>;
// How many rows of the table have the state role.
inline constexpr std::size_t kStateRows = [] {
  std::size_t n = 0;
  for_each_particle_member([&](const auto& info, auto) { n += info.role == ArrayRole::state; });
  return n;
}();
}  // namespace detail
inline constexpr auto kStateArrays = [] {
  std::array<StateArray, detail::kStateRows> out{};
  std::size_t k = 0;
  for_each_particle_member([&](const auto& info, auto member) {
    if constexpr (detail::holds_doubles<std::decay_t<decltype(info)>>)
      if (info.role == ArrayRole::state) out[k++] = {info.name, member, info.dims};
  });
  return out;
}();
static_assert(
    [] {
      for (const StateArray& a : kStateArrays)
        if (a.member == nullptr) return false;
      return true;
    }(),
    "a state array must hold doubles");

// The state arrays a store of `dimension` holds, in the table's order.
const std::vector<StateArray>& state_arrays(int dimension);

}  // namespace mpsolid
