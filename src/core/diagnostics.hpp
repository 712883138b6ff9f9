#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>
// Whole-system figures at a frame: energies (MODEL.md section 4b), momenta
// (about the origin, spins included) and the largest speed.
#include "src/core/solver_state.hpp"

namespace mpsolid {

// The gas's figures (a case with [gas]): its steps, its totals and what it
// exchanged (J, over the depth), and its probes.
struct GasFigures {
  std::int64_t gas_steps = 0;
  double gas_time = 0;          // s: how far the gas has stepped
  double mass = 0, energy = 0;  // kg, J
  double inflow_energy = 0;     // J: in through the grid's edges since the start
  double wall_work = 0;         // J: the gas's work on the bodies
  double solid_work = 0;        // J: the reference pressure's work on the bodies
  double lost_energy = 0;       // J: in cells covered with no gas next to them
  // J: the bodies' work from their gas loads less what the gas and the
  // reference pressure did on them (the coupling windows' error).
  double coupling_error = 0;
  std::vector<double> probe_p, probe_rho;  // at each probe (NaN inside a body)
};

struct Diagnostics {
  double kinetic_energy = 0;  // translational + rotational
  double strain_energy = 0;
  double contact_energy = 0;  // 0 without contact
  // The smallest distance between two contact candidates that may touch,
  // capped at the search's reach (0 without contact).
  double contact_min_distance = 0;
  double external_work = 0;
  double damping_loss = 0;  // the energy damping took out (0 without [damping])
  double momentum_x = 0, momentum_y = 0;
  double momentum_z = 0;  // 0 in the plane
  // About the origin, spins included: about z, and in space about x and y.
  double angular_momentum = 0;
  double angular_momentum_x = 0, angular_momentum_y = 0;
  double max_speed = 0;
  GasFigures gas;  // zeros without a gas
};

// |v_i|^2 (vz in space only).
inline double speed_squared(const ParticleStore& p, std::size_t i) {
  const double v2 = p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i];
  return p.dimension == 3 ? v2 + p.vz[i] * p.vz[i] : v2;
}

// Kinetic energy, momenta and max speed of the moving particles.
Diagnostics motion_diagnostics(const ParticleStore& p);

// What motion_diagnostics sums per particle, in ordered sums of one
// component each: kinetic energy, momentum x, y, z, angular momentum about
// x, y, z, damping loss (in the plane z momentum and the x, y angular
// momenta are 0), and the figures from the sums and the largest |v|^2 (the
// same from the whole state or from ranks' shares).
inline constexpr std::size_t kMotionSums = 8;
std::array<double, kMotionSums> motion_terms(const ParticleStore& p, std::size_t i);
Diagnostics motion_from_sums(const std::array<double, kMotionSums>& sums, double max_speed2);

// What a history row reads of the particles besides the sums: each elastic
// body's extent (min and max of x, y and, in space, z; in the case's body
// order), each probe's position and each load's work so far (from the whole
// state, or from the ranks' shares: src/solver/rank_checks.hpp).
struct HistoryReadings {
  std::vector<std::array<double, 6>> extents;
  std::vector<std::array<double, 3>> probes;
  std::vector<double> load_work;
};
// The extent of the particles of `range`: min and max of x, y and, in
// space, z (+inf, -inf where `range` is empty; z 0 in the plane), the first
// smallest and the last largest as std::minmax_element finds them; and a
// later part's extent (in storage order) added to it, as if scanned after.
std::array<double, 6> extent_of(const ParticleStore& p, Range range);
void widen(std::array<double, 6>& extent, const std::array<double, 6>& later);
// A particle's position (z 0 in the plane).
std::array<double, 3> position_of(const ParticleStore& p, std::size_t i);

// Everything, with the model's strain energy already summed (in the ordered
// sums' chunk order, on one rank or from the ranks' chunk sums).
Diagnostics diagnostics_with_strain_energy(const SolverState& s, double strain_energy);

}  // namespace mpsolid
