#pragma once
// The decomposed step against the serial run, threads as ranks.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/distributed/decomposition.hpp"

namespace mpsolid::testing {

// After `steps` steps of `spec` on the cut `cut_of` makes of its set-up
// state (its ranks the threads of a team), every owned particle's position
// and velocity, and each rank's pose and driver's work of every rigid body
// it holds, compared with the serial run's bits: the first difference
// found on each rank (empty where none).
std::vector<std::string> serial_bits_failures(
    const CaseSpec& spec, std::int64_t steps,
    const std::function<Decomposition(const SolverState&)>& cut_of);

}  // namespace mpsolid::testing
