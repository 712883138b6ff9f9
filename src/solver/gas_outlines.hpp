#pragma once
// The bodies' outlines as the gas sees them (docs/gas.md): each coupled
// body's whole surface over the particles of the whole state or of a rank's
// part, its nodes' positions and velocities at the start of a gas window,
// and the node forces the gas then gives each moving body's gas load. Over
// MPI ranks every part holds every outline and positions the nodes it hosts
// (a node's first weight it owns: its other weights are that particle's
// bond partners); the ranks share them, and every part closes its gas
// loads' running step at them and takes the forces: the whole state's bits
// with no rank holding the whole.
#include <cstddef>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/loads.hpp"
#include "src/core/solver_state.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/rank_group.hpp"
#include "src/solver/distributed_step.hpp"

namespace mpsolid {

// Each body the gas pushes gets a load named kGasLoadPrefix + its name: a
// pressure load over its whole surface whose node forces the gas gives.
inline constexpr const char* kGasLoadPrefix = "gas.";

// Every coupled body's whole surface (every segment), in the order of the
// case's [gas] bodies, its sites at the storage indices its body's range
// in `body_ranges` (the whole state's) begins at.
std::vector<PressureSurface> gas_outlines(const CaseSpec& spec,
                                          const std::vector<Range>& body_ranges);
// The same as a rank's part holds them (`layout`: its particles), each
// positioning the nodes whose host it owns: a moving body's is its gas
// load's surface among the part's `loads`, a wall's made from its shape.
std::vector<PressureSurface> part_gas_outlines(const CaseSpec& spec,
                                               const std::vector<StepLoad>& loads,
                                               const std::vector<Range>& body_ranges,
                                               const LocalLayout& layout);

// The gas loads of the case's coupled moving bodies (walls never move: no
// load), in the order of its [gas] bodies, over the whole state's storage
// indices (`body_ranges`), their node forces zero until the gas gives them.
std::vector<StepLoad> gas_loads(const CaseSpec& spec, const std::vector<Range>& body_ranges);

// The outlines' nodes at an instant: x, y, vx, vy of each node in node
// order, outline by outline.
using OutlineMotion = std::vector<std::vector<double>>;

// Every node's, from the whole state's particles.
OutlineMotion outline_motion(const ParticleStore& p, const std::vector<PressureSurface>& outlines);
// The nodes a part hosts, appended as (outline, node, x, y, vx, vy) each.
void append_hosted_outline_motion(const ParticleStore& p,
                                  const std::vector<PressureSurface>& outlines,
                                  std::vector<double>& out);
// Every node's, from every part's hosted nodes (any order).
OutlineMotion assemble_outline_motion(const std::vector<PressureSurface>& outlines,
                                      const std::vector<double>& hosted);
// Every node's, on every rank of `world` (collective): each rank's part
// positions the nodes of `outlines` (its part_gas_outlines) it hosts, its
// ghosts brought up to date first, and the ranks share them.
OutlineMotion shared_outline_motion(RankPart& part, const std::vector<PressureSurface>& outlines,
                                    const RankGroup& world);

// The gas's node forces (N) on the gas loads, in the order of gas_loads:
// each load's x components then its y components, node by node.
using GasNodeForces = std::vector<double>;

// Gives `forces` to the gas loads among `loads` (the whole state's or a
// part's): each one's running step closed at its nodes' positions in
// `motion` (the work so far added up), its node forces set and, once it is
// on, the forces on its particles.
void give_gas_forces(const CaseSpec& spec, std::vector<StepLoad>& loads,
                     const OutlineMotion& motion, const GasNodeForces& forces);

}  // namespace mpsolid
