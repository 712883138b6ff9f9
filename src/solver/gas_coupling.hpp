#pragma once
// The gas of a case's [gas] section, coupled both ways to its bodies
// (MODEL.md section 9, docs/gas.md). The solid steps in windows of whole
// steps; at the start of each window the bodies' outlines (their surfaces'
// nodes, as their particles place them, with their velocities) become the
// walls in the gas, the gas steps over the window (one gas step, or several
// when one solid step is longer than the gas's CFL step), and the gas's
// forces on each outline's segments, split to their ends, become node
// forces held over the window: each moving body's gas load
// (src/core/loads.hpp). What the gas gives is what the walls take in each
// gas stage; the windows' error is the work of the held forces against the
// nodes' actual motion, kept in the balance.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/gas/gas_solver.hpp"

namespace mpsolid {

// Each body the gas pushes gets a load named kGasLoadPrefix + its name: a
// pressure load over its whole surface whose node forces the gas gives.
inline constexpr const char* kGasLoadPrefix = "gas.";

// The gas loads of `spec`'s coupled moving bodies, appended to s.loads
// (at set-up, after the case's own loads).
void add_gas_loads(const CaseSpec& spec, SolverState& s);

// One row of the gas's figures for history.csv and run.json.
struct GasFigures {
  std::int64_t gas_steps = 0;
  double gas_time = 0;                     // s: how far the gas has stepped
  double mass = 0, energy = 0;             // kg, J (per metre of depth times the depth)
  double inflow_energy = 0;                // J: through the grid's edges since the start
  double wall_work = 0;                    // J: the gas's work on the bodies
  double solid_work = 0;                   // J: the reference pressure's work on the bodies
  double lost_energy = 0;                  // J: in cells covered with no gas next to them
  std::vector<double> probe_p, probe_rho;  // at each probe (NaN inside a body)
};

class GasCoupling {
 public:
  // The gas's grid, initial state and walls from `spec` and the bodies in
  // `state` (whose gas loads add_gas_loads made).
  GasCoupling(const CaseSpec& spec, const SolverState& state);
  ~GasCoupling();

  // The step at which the next window starts (the gas is due).
  std::int64_t next_exchange() const { return next_; }
  // At state.step == next_exchange(): the walls from the state, the gas
  // stepped over the window, the gas loads' node forces set. Throws
  // GasFailure (the gas as it was) when the gas went unphysical.
  void exchange(SolverState& state, double dt);

  GasFigures figures() const;
  const GasSolver<2>& gas() const { return *gas_; }

 private:
  struct Outline;  // a coupled body's surface as the gas sees it
  std::vector<GasWallSegment> walls(const SolverState& state) const;

  GasSpec spec_;
  double depth_;
  std::unique_ptr<GasSolver<2>> gas_;
  std::vector<Outline> outlines_;
  std::int64_t next_ = 0;
  std::int64_t gas_steps_ = 0;
  double gas_time_ = 0;
};

}  // namespace mpsolid
