#pragma once
// The initial velocities a case asks for (BodySpec velocity, spin and
// bending_mode), applied once after set-up. Held components start at zero.
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"

namespace mpsolid {

// v_y / tip_velocity of a bending mode at x (MODEL.md section 6).
double bending_mode_shape(const BendingMode& mode, double x);

void apply_initial_motion(SolverState& s, const CaseSpec& spec, bool with_rotation);

}  // namespace mpsolid
