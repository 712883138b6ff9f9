#pragma once
// The initial velocities a case asks for (BodySpec velocity, spin and
// bending_mode), applied once after set-up. Held components start at zero.
#include <array>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"

namespace mpsolid {

// v_y / tip_velocity of a bending mode at x (MODEL.md section 6).
double bending_mode_shape(const BendingMode& mode, double x);

// Each elastic body's spin turns about the centroid of its particles: of
// `s`'s body ranges, or given (`centroids`, per body) for a state that
// holds only part of a body (a rank's part).
void apply_initial_motion(SolverState& s, const CaseSpec& spec, bool with_rotation,
                          const std::vector<std::array<double, 3>>* centroids = nullptr);

}  // namespace mpsolid
