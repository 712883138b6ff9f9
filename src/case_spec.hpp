#pragma once
// A fully validated case, in SI units. Produced by read_case(); everything
// downstream trusts it.
#include <cstdint>
#include <string>
#include <vector>

#include "kernels/model_common.hpp"
#include "src/material.hpp"
#include "src/types.hpp"

namespace mpsolid {

struct BodySpec {
  std::string name;
  Kind kind = Kind::elastic;
  int material = 0;      // index into CaseSpec::materials
  double x[2] = {0, 0};  // rectangle [x0, x1] (m)
  double y[2] = {0, 0};  // rectangle [y0, y1] (m)
};

// A step force: total force (N over the depth) on a body from `start` on,
// shared equally by its particles.
struct LoadSpec {
  std::string name;
  int body = 0;  // index into CaseSpec::bodies
  double force[2] = {0, 0};
  double start = 0;
};

// Blow-up checks, run every `check_interval` steps.
struct StabilitySpec {
  std::int64_t check_interval = 500;  // steps
  double max_speed = 1.0;             // in units of the largest dilatational wave speed
  double energy_tolerance = 0.1;      // |KE + PE - W - E0| / max(W, E0)
};

struct CaseSpec {
  std::string name;    // output folder name (default: the file's stem)
  std::string source;  // the case file it came from
  std::string model = "paper";
  double l0 = 0;       // lattice spacing (m)
  double depth = 1.0;  // out-of-plane depth D (m)
  std::vector<Material> materials;
  std::vector<BodySpec> bodies;  // in name order: this fixes the particle ids
  std::vector<LoadSpec> loads;
  double dt = 0;
  double end = 0;
  double frame_interval = 0;
  double checkpoint_interval = 0;  // s; 0: only at the end of the run (and on a stop signal)
  int compression = 0;             // deflate level of frames.h5: 0 (off) to 9
  ModelOptions model_options;      // hourglass (finite_strain) and min_jacobian (stability)
  StabilitySpec stability;
  std::string resolved_toml;  // the case with every default and override filled in

  std::int64_t step_count() const;            // steps to reach `end`
  std::int64_t steps_per_frame() const;       // output cadence in steps
  std::int64_t steps_per_checkpoint() const;  // checkpoint cadence in steps; 0: none
};

}  // namespace mpsolid
