#pragma once
// The bond table of a set-up lattice: every pair of particles closer than re
// in the reference configuration, found by a neighbour search on x0, y0 (and z0 in space).
#include "neighbor/neighbor_lists.hpp"
#include "src/core/bonds.hpp"

namespace mpsolid {

BondTable build_bonds(const ParticleStore& particles, const BondGeometry& geometry,
                      NeighborMethod method = NeighborMethod::cell_list);

}  // namespace mpsolid
