#pragma once
// The fixed bond table (total Lagrangian): every pair closer than re in the
// initial configuration, stored from both ends in compressed rows, with the
// reference bond vectors. Topology and reference geometry only: each model
// makes its own per-bond coefficients from them (kernels/). Built once.
#include <cstdint>
#include <vector>

#include "src/core/particle_store.hpp"

namespace mpsolid {

// The lattice the bonds were found on.
struct BondGeometry {
  double l0 = 0;      // lattice spacing (m)
  double re = 0;      // interaction radius, 2.1 l0 (MODEL.md section 1)
  double volume = 0;  // particle volume: l0^2 * depth in the plane, l0^3 in space (m^3)
  int dimension = 2;  // the lattice's: square (2) or cubic (3)
};

inline constexpr double kRadiusOverSpacing = 2.1;

BondGeometry bond_geometry(double l0, double depth);
// In space: a cube of side l0 per particle.
BondGeometry bond_geometry_3d(double l0);

struct BondTable {
  std::vector<std::uint32_t> offsets;   // size n + 1
  std::vector<std::uint32_t> neighbor;  // j, ascending within a row
  std::vector<double> r0x, r0y, r0z;    // r0_ij = r0_j - r0_i (r0z empty in the plane)
  BondGeometry geometry;

  std::size_t particle_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t entry_count() const { return neighbor.size(); }  // each bond twice
  std::uint32_t begin(std::size_t i) const { return offsets[i]; }
  std::uint32_t end(std::size_t i) const { return offsets[i + 1]; }
  // Hash of the topology and the reference vectors (checks checkpoints).
  std::uint64_t hash() const;
};

// The table for neighbour lists (compressed rows, ascending within a row) of
// the reference positions; neighbor/bond_search.hpp finds them.
BondTable make_bond_table(const ParticleStore& particles, std::vector<std::uint32_t> offsets,
                          std::vector<std::uint32_t> neighbor, const BondGeometry& geometry);

}  // namespace mpsolid
