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
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/diagnostics.hpp"
#include "src/core/gas_frame.hpp"
#include "src/core/solver_state.hpp"
#include "src/gas/gas_solver.hpp"
#include "src/solver/gas_outlines.hpp"

namespace mpsolid {

class GasCoupling {
 public:
  // The gas's grid and initial state from `spec`, its outlines over the
  // whole state's storage indices (`head`: its bodies' ranges, gas loads
  // and rigid bodies, with or without the particles); its walls wait for
  // place_walls.
  GasCoupling(const CaseSpec& spec, const SolverState& head);

  // The bodies' outlines (in the case's [gas] order) whose nodes' motion
  // the gas reads (outline_motion, or the ranks' hosted nodes).
  const std::vector<PressureSurface>& outlines() const { return outlines_; }
  // The outlines' nodes `now` as the gas's walls (at set-up).
  void place_walls(const OutlineMotion& now);

  std::int64_t steps() const { return gas_steps_; }
  // The step at which the next window starts (the gas is due).
  std::int64_t next_exchange() const { return next_; }
  // At head.step == next_exchange(): the walls from the outlines' nodes
  // `now`, the gas stepped over the window; returns the node forces the gas
  // loads hold over it (give_gas_forces). `head`'s rigid bodies must be
  // current (a driven body's motion bounds the window). Throws GasFailure
  // (the gas as it was) when the gas went unphysical.
  GasNodeForces window(const SolverState& head, const OutlineMotion& now, double dt);

  // Everything a resumed run needs to go on with the same bits, as named
  // arrays (for checkpoint.h5), and put back from them (after the state's
  // restore). Throws InputError when they do not fit this gas.
  using Saved = std::vector<std::pair<std::string, std::vector<double>>>;
  Saved saved() const;
  void restore(const Saved& saved);

  // The figures, with the coupling error from the gas loads' work
  // (`work_of(l)`: the work of head.loads[l] so far).
  GasFigures figures(const std::function<double(std::size_t)>& work_of) const;
  const GasSolver<2>& gas() const { return gas_; }
  // The gas's fields now, for a frame.
  GasFrame frame() const;

 private:
  // A coupled body as the gas sees it: its gas load in SolverState::loads
  // (-1 for a wall), and its outline's first segment among the gas's walls.
  struct Outline {
    int load = -1;
    int driven = -1;  // its rigid body in SolverState::rigid_bodies when driven
    std::size_t first_piece = 0;
  };
  std::vector<GasWallSegment> walls(const OutlineMotion& now) const;
  // How many of the next `limit` solid steps keep every wall within half a
  // cell of where the gas last saw it: the free walls at their present
  // speed `fastest`, the driven ones at their motion's speed step by step.
  double steps_within_half_a_cell(const SolverState& head, double dt, double fastest,
                                  double limit) const;

  GasSpec spec_;
  double depth_;
  GasSolver<2> gas_;
  std::vector<GasWallSegment> last_walls_;  // as the gas has them
  std::vector<PressureSurface> outlines_;
  std::vector<Outline> coupled_;  // each outline's load and rigid body
  std::int64_t next_ = 0;
  std::int64_t gas_steps_ = 0;
  double gas_time_ = 0;
};

}  // namespace mpsolid
