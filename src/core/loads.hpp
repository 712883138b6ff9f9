#pragma once
// External step forces on bodies, shared equally by a body's particles, and
// the work they do.
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/particle_store.hpp"

namespace mpsolid {

struct StepLoad {
  std::string name;
  Range range;                  // the loaded body's particles
  double fx = 0, fy = 0;        // total force (N)
  std::int64_t first_step = 0;  // first step k with k dt >= start
  // Centroid of the body at first_step, once reached. For a constant force,
  // the work telescopes: W = F . (c(now) - c(first_step)), exactly, because
  // each step moves every particle by dt v and W_step = sum (F/N) . dt v.
  bool active = false;
  double cx_on = 0, cy_on = 0;
};

// Switches on the loads that start at or before `step`, recording the
// body's centroid (call with the step's start-of-step positions).
void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step);

// Adds each active load's share to the forces of the particles in `block`
// (after the force pass), loads in order. Serial: the step calls it per block.
void apply_loads(ParticleStore& p, const std::vector<StepLoad>& loads, Range block);

// Work done by all loads up to the current state.
double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads);

// Centroid of a range of particles (ordered sum).
void centroid(const ParticleStore& p, Range range, double& cx, double& cy);

}  // namespace mpsolid
