#pragma once
// Rigid bodies split between ranks (docs/mpi.md). A rigid body too large to
// keep on one rank without unbalancing the cut is owned by several: each
// holds the body's pose and make-up (its offsets for its own particles
// only), adds the projection's terms (ProjectionTerms) of its own particles
// as its part of the serial ordered sum, with the chunks it shares finished
// over the ranks, and combines the whole sum from every rank's chunk sums.
// So each rank advances the same pose, bit for bit the serial one, and
// places its own particles; one all-gather per step serves every split body.
#include <cstdint>
#include <string>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/halo_exchange.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/rank_group.hpp"

namespace mpsolid {

struct SplitRigidBody {
  std::string name;
  Range global;             // the body's storage range in the run
  std::int64_t local = -1;  // its place among this part's rigid bodies; -1: it holds none
};

// The case's rigid bodies that `d` gives to more than one rank (`body_ranges`:
// every body's global range), in the case's order, the same on every rank.
std::vector<SplitRigidBody> split_rigid_bodies(const CaseSpec& spec,
                                               const std::vector<Range>& body_ranges,
                                               const Decomposition& d,
                                               const std::vector<RigidBody>& mine);

// Projects every split body (collective over `world`, every rank calling it
// with the same list): at the end of the step from t = step dt.
void project_split_rigid_bodies(const std::vector<SplitRigidBody>& split, SolverState& s,
                                const LocalLayout& layout, const Decomposition& d,
                                const RankGroup& world, HaloCost& cost, double t, double dt,
                                bool with_rotation);

}  // namespace mpsolid
