#include "neighbor/bond_search.hpp"

namespace mpsolid {

BondTable build_bonds(const ParticleStore& particles, const BondGeometry& geometry,
                      NeighborMethod method) {
  NeighborLists lists =
      find_neighbors({particles.x0, particles.y0, particles.z0}, geometry.re, method);
  return make_bond_table(particles, std::move(lists.offsets), std::move(lists.indices), geometry);
}

}  // namespace mpsolid
