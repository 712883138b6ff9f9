#include "src/core/stability.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace mpsolid {

bool state_is_finite(const ParticleStore& p, std::size_t i) {
  // Every state row of the store's dimension (positions, velocities,
  // rotations, spins).
  const std::vector<StateArray> arrays = state_arrays(p.dimension);
  return std::all_of(arrays.begin(), arrays.end(),
                     [&](const StateArray& a) { return std::isfinite((p.*a.member)[i]); });
}

StabilityVerdict non_finite_verdict(std::size_t particle) {
  StabilityVerdict v;
  v.ok = false;
  v.criterion = "non-finite state (NaN or Inf in position, velocity or rotation)";
  v.particle = particle;
  return v;
}

StabilityVerdict check_finite(const ParticleStore& p) {
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!state_is_finite(p, i)) return non_finite_verdict(i);
  return {};
}

Fastest fastest_moving(const ParticleStore& p) {
  const Range r = p.moving();
  Fastest f;
  for (std::size_t i = r.begin; i < r.end; ++i) {
    const double s2 = speed_squared(p, i);
    if (s2 > f.speed2) f = {i, s2};
  }
  return f;
}

StabilityVerdict check_speed(const ParticleStore& p, double limit_speed) {
  return speed_verdict(fastest_moving(p), limit_speed);
}

StabilityVerdict speed_verdict(const Fastest& fastest, double limit_speed) {
  StabilityVerdict v;
  v.particle = fastest.particle;
  v.value = std::sqrt(std::max(fastest.speed2, 0.0));
  v.limit = limit_speed;
  if (v.value > limit_speed) {
    v.ok = false;
    v.criterion = fmt::format("speed {:.4g} m/s above the limit {:.4g} m/s", v.value, limit_speed);
  }
  return v;
}

StabilityVerdict check_energy(const Diagnostics& d, double initial_energy, double peak_work,
                              double tolerance, double floor) {
  StabilityVerdict v;
  const double scale =
      std::max({std::abs(d.external_work), peak_work, std::abs(initial_energy), floor});
  // PE: the strain energy and the contact energy; D: what damping took out.
  v.value = d.kinetic_energy + d.strain_energy + d.contact_energy + d.damping_loss -
            d.external_work - initial_energy;
  v.limit = tolerance * scale;
  if (scale > 0.0 && std::abs(v.value) > v.limit) {
    v.ok = false;
    v.criterion = fmt::format(
        "energy balance: KE + PE + D - W - E0 = {:.4g} J, more than {:g} of max(peak W, E0) = "
        "{:.4g} J",
        v.value, tolerance, scale);
  }
  return v;
}

double energy_balance_floor(const std::vector<ParticleGroup>& groups, double particle_volume) {
  double sum = 0;
  for (const ParticleGroup& g : groups)
    sum += static_cast<double>(g.particles) * (g.material.lambda() + 2 * g.material.mu());
  return 0.5e-12 * sum * particle_volume;
}

double dilatational_wave_speed(const std::vector<Material>& materials) {
  double c = 0.0;
  for (const Material& m : materials)
    c = std::max(c, std::sqrt((m.lambda() + 2.0 * m.mu()) / m.density));
  return c;
}

}  // namespace mpsolid
