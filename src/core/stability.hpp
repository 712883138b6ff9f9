#pragma once
// Blow-up diagnosis: cheap checks of the current state, each naming the
// particle where it fails. Run every `stability.check_interval` steps.
#include <cstdint>
#include <string>

#include <vector>

#include "src/core/diagnostics.hpp"
#include "src/core/material.hpp"

namespace mpsolid {

struct StabilityVerdict {
  bool ok = true;
  std::string criterion;     // which check failed, in words
  std::size_t particle = 0;  // storage index of the particle where it failed
  std::size_t neighbor = 0;  // its bond partner, for a per-bond criterion
  bool has_neighbor = false;
  // How the message names the neighbour: its bond partner, or the particle
  // that came too close (contact).
  const char* neighbor_role = "bonded to";
  double value = 0, limit = 0;
  // What failed and where, in words, when no particle is to blame (the gas).
  std::string where;
};

// First non-finite position, velocity, rotation or angular velocity.
StabilityVerdict check_finite(const ParticleStore& p);
// Whether particle i's state is finite, and the verdict naming the first
// that is not (check_finite's, from the whole state or from ranks).
bool state_is_finite(const ParticleStore& p, std::size_t i);
StabilityVerdict non_finite_verdict(std::size_t particle);

// The fastest moving particle against the limit speed.
StabilityVerdict check_speed(const ParticleStore& p, double limit_speed);
// The first fastest moving particle and its |v|^2 (-1: no moving particle),
// and check_speed's verdict of it (from the whole state or from ranks).
struct Fastest {
  std::size_t particle = 0;
  double speed2 = -1.0;
};
Fastest fastest_moving(const ParticleStore& p);
StabilityVerdict speed_verdict(const Fastest& fastest, double limit_speed);

// |KE + PE - W - E0| against tolerance * max(peak W, E0, floor); the peak
// external work so far, not the current W, which falls when the body pushes
// back. `floor`: the energy below which the balance is round-off (a body at
// rest before any load reaches it).
StabilityVerdict check_energy(const Diagnostics& d, double initial_energy, double peak_work,
                              double tolerance, double floor = 0.0);

// The energy floor of the balance: the strain energy of a uniform strain
// of 1e-6 in every particle, sum over particles of (lambda + 2 mu) V 1e-12 /
// 2, from each group's particle count and material (one group per body:
// no rank need hold the particles).
struct ParticleGroup {
  std::size_t particles;
  Material material;
};
double energy_balance_floor(const std::vector<ParticleGroup>& groups, double particle_volume);

// Largest dilatational wave speed sqrt((lambda + 2 mu) / rho) of the case's materials.
double dilatational_wave_speed(const std::vector<Material>& materials);

}  // namespace mpsolid
