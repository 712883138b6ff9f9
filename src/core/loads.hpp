#pragma once
// External forces on bodies, shared equally by a body's particles, each
// following its time history (src/core/load_history.hpp), and the work they
// do.
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

struct StepLoad {
  std::string name;
  Range range;                  // the loaded body's particles
  double fx = 0, fy = 0;        // total force (N) at a factor of 1
  LoadHistory history;          // the factor over time since `start`
  double start = 0;             // s: when it switches on
  std::int64_t first_step = 0;  // first step k with k dt >= start
  // Centroid of the body at first_step, once reached. For a constant force,
  // the work telescopes: W = F . (c(now) - c(first_step)), exactly, because
  // each step moves every particle by dt v and W_step = sum (F/N) . dt v.
  bool active = false;
  double cx_on = 0, cy_on = 0;
  // A varying force: the factor of the step that ran last (or runs now),
  // the centroid at that step's start, and the work of the steps before it.
  double factor = 1;
  double cx_last = 0, cy_last = 0;
  double work = 0;
};

// At the start of `step` (with its start-of-step positions): switches on
// the loads that start at it, recording the body's centroid, and for the
// varying ones adds the previous step's work and takes this step's factor.
void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                    double dt);

// Adds each active load's share to the forces of the particles in `block`
// (after the force pass), loads in order. Serial: the step calls it per block.
void apply_loads(ParticleStore& p, const std::vector<StepLoad>& loads, Range block);

// Work done by one load, and by all, up to the current state.
double load_work(const ParticleStore& p, const StepLoad& load);
double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads);

// Centroid of a range of particles (ordered sum).
void centroid(const ParticleStore& p, Range range, double& cx, double& cy);

}  // namespace mpsolid
