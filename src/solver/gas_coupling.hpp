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
#include <string>
#include <utility>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/diagnostics.hpp"
#include "src/core/gas_frame.hpp"
#include "src/core/solver_state.hpp"
#include "src/gas/gas_solver.hpp"

namespace mpsolid {

// Each body the gas pushes gets a load named kGasLoadPrefix + its name: a
// pressure load over its whole surface whose node forces the gas gives.
inline constexpr const char* kGasLoadPrefix = "gas.";

// The gas loads of `spec`'s coupled moving bodies, appended to s.loads
// (at set-up, after the case's own loads).
void add_gas_loads(const CaseSpec& spec, SolverState& s);

class GasCoupling {
 public:
  // The gas's grid, initial state and walls from `spec` and the bodies in
  // `state` (whose gas loads add_gas_loads made).
  GasCoupling(const CaseSpec& spec, const SolverState& state);

  std::int64_t steps() const { return gas_steps_; }
  // The step at which the next window starts (the gas is due).
  std::int64_t next_exchange() const { return next_; }
  // At state.step == next_exchange(): the walls from the state, the gas
  // stepped over the window, the gas loads' node forces set. Throws
  // GasFailure (the gas as it was) when the gas went unphysical.
  void exchange(SolverState& state, double dt);

  // Everything a resumed run needs to go on with the same bits, as named
  // arrays (for checkpoint.h5), and put back from them (after the state's
  // restore). Throws InputError when they do not fit this gas.
  using Saved = std::vector<std::pair<std::string, std::vector<double>>>;
  Saved saved() const;
  void restore(const Saved& saved);

  // The figures, with the coupling error from the gas loads' work in `state`.
  GasFigures figures(const SolverState& state) const;
  const GasSolver<2>& gas() const { return gas_; }
  // The gas's fields now, for a frame.
  GasFrame frame() const;

 private:
  // A coupled body's surface as the gas sees it: its nodes' weights and its
  // segments, its gas load in SolverState::loads (-1 for a wall), and its
  // first segment among the gas's walls.
  struct Outline {
    PressureSurface surface;
    int load = -1;
    int driven = -1;  // its rigid body in SolverState::rigid_bodies when driven
    std::size_t first_piece = 0;
  };
  std::vector<GasWallSegment> walls(const SolverState& state) const;
  // How many of the next `limit` solid steps keep every wall within half a
  // cell of where the gas last saw it: the free walls at their present
  // speed `fastest`, the driven ones at their motion's speed step by step.
  double steps_within_half_a_cell(const SolverState& state, double dt, double fastest,
                                  double limit) const;

  GasSpec spec_;
  double depth_;
  GasSolver<2> gas_;
  std::vector<GasWallSegment> last_walls_;  // as the gas has them
  std::vector<Outline> outlines_;
  std::int64_t next_ = 0;
  std::int64_t gas_steps_ = 0;
  double gas_time_ = 0;
};

}  // namespace mpsolid
