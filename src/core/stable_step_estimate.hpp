#pragma once
// The result of the stable-step estimate (src/solver/stable_step.hpp), as the
// run report and the closing summary show it.
namespace mpsolid {

struct StableStepEstimate {
  double omega_max = 0;  // rad/s
  double dt_limit = 0;   // 2 / omega_max (s)
  int iterations = 0;    // 0: no estimate (dt was given)
  bool converged = false;
};

}  // namespace mpsolid
