#pragma once
// Structure-of-arrays particle store. Particles are grouped by kind in storage
// order [wall | elastic | rigid body 0 | rigid body 1 | ...] so hot loops run
// over index ranges. Stable ids (creation order) are separate from storage
// order; outputs are written in id order.
#include <cstdint>
#include <vector>

#include "src/core/types.hpp"

namespace mpsolid {

struct ParticleStore {
  // State.
  std::vector<double> x, y;    // position (m)
  std::vector<double> vx, vy;  // velocity (m/s)
  std::vector<double> theta;   // rotation angle (rad)
  std::vector<double> omega;   // angular velocity (rad/s)

  // Reference configuration.
  std::vector<double> x0, y0;

  // Per-step work arrays.
  std::vector<double> half_cos, half_sin;  // cos(theta/2), sin(theta/2)
  std::vector<double> strain;              // volumetric strain eps_i
  std::vector<double> pressure;            // p_i = -lambda_i eps_i
  std::vector<double> fx, fy;              // force (N, over the depth)
  std::vector<double> torque;              // torque (N m)

  // Constants.
  std::vector<double> inv_mass, inv_inertia;
  std::vector<double> lambda;  // Lame lambda of the particle's material
  std::vector<double> mu;      // Lame mu of the particle's material
  std::vector<std::int32_t> id, body, material;
  std::vector<Kind> kind;

  // Storage ranges by kind.
  Range walls, elastic, rigid;

  std::size_t size() const { return x.size(); }
  // Particles whose motion is integrated (elastic and rigid).
  Range moving() const { return {elastic.begin, rigid.end}; }
  Range all() const { return {0, size()}; }

  void resize(std::size_t n);
  // Storage index of each id (inverse of `id`).
  std::vector<std::size_t> storage_of_id() const;
};

// The per-particle arrays that evolve in time: positions, velocities,
// rotations and angular velocities. The rest of the store is constant from
// set-up (x0, masses, ids, ...) or recomputed from these every step (half
// angles, strain, pressure, forces, torques). Snapshots and checkpoints copy
// exactly these; a model with per-particle state of its own adds it here.
struct StateArray {
  const char* name;
  std::vector<double> ParticleStore::*member;
};
inline constexpr StateArray kStateArrays[] = {
    {"x", &ParticleStore::x},   {"y", &ParticleStore::y},         {"vx", &ParticleStore::vx},
    {"vy", &ParticleStore::vy}, {"theta", &ParticleStore::theta}, {"omega", &ParticleStore::omega}};

}  // namespace mpsolid
