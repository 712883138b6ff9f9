#pragma once
// The fixed bond table (total Lagrangian): every pair closer than re in the
// initial configuration, stored from both ends in compressed rows, with the
// per-bond constants the kernels need. Built once; never changes.
#include <cstdint>
#include <vector>

#include "neighbor/neighbor_lists.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

struct KernelConstants {
  double l0 = 0;      // lattice spacing (m)
  double re = 0;      // interaction radius, 2.1 l0
  double n0 = 0;      // initial number density of a full interior neighbourhood
  double volume = 0;  // particle volume l0^2 * depth (m^3)
};

inline constexpr double kRadiusOverSpacing = 2.1;

// n0 = sum_j w(|r0_ij|) over a full square-lattice neighbourhood.
double lattice_number_density(double l0, double re);
KernelConstants kernel_constants(double l0, double depth);

struct BondTable {
  std::vector<std::uint32_t> offsets;   // size n + 1
  std::vector<std::uint32_t> neighbor;  // j, ascending within a row
  std::vector<double> r0x, r0y;         // r0_ij = r0_j - r0_i
  std::vector<double> strain_coef;      // (d / n0) w0_ij / |r0_ij|
  std::vector<double> spring_coef;      // k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (N/m)
  KernelConstants constants;

  std::size_t particle_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t entry_count() const { return neighbor.size(); }  // each bond twice
  std::uint32_t begin(std::size_t i) const { return offsets[i]; }
  std::uint32_t end(std::size_t i) const { return offsets[i + 1]; }
  // FNV-1a hash of the topology and reference vectors (checks checkpoints).
  std::uint64_t hash() const;
};

// Bond constants from neighbour lists over the reference positions. mu_ij is
// the arithmetic mean of the two particles' mu.
BondTable make_bond_table(const ParticleStore& particles, const NeighborLists& lists,
                          const KernelConstants& constants);

// Convenience: cell-list search on x0, y0, then make_bond_table.
BondTable build_bonds(const ParticleStore& particles, const KernelConstants& constants,
                      NeighborMethod method = NeighborMethod::cell_list);

}  // namespace mpsolid
