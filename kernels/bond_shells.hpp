#pragma once
// A bond table's lattice shells. Every body fills one global lattice, so
// almost every bond's reference length is l0 sqrt(n) for a small integer n
// (n = 1, 2, 4 in the plane; 1, 2, 3, 4 in space): each entry keeps one
// byte naming its shell, and a gather reads a bond's length-dependent
// constants from a table of a few values instead of computing a square root
// and a division per bond and pass. A length within 1e-9 of a shell's
// (decimal round-off in the sites' coordinates) is given the shell's exact
// value; an entry off every shell (`kOff`: bodies placed off the lattice)
// has its constants computed. Both ends of a bond have the same length bits,
// so they name the same shell.
#include <cmath>
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

struct BondShells {
  static constexpr std::uint8_t kOff = 255;
  std::vector<std::uint8_t> of_entry;  // shell of each bond table entry, or kOff
  std::vector<double> length;          // l0 sqrt(n) of each shell (m)
};

// |r0_ij|^2, summed x, y, z.
inline double reference_length2(const ParticleStore& p, std::size_t i, std::size_t j) {
  const double dx = p.x0[j] - p.x0[i], dy = p.y0[j] - p.y0[i];
  double len2 = dx * dx + dy * dy;
  if (p.dimension == 3) {
    const double dz = p.z0[j] - p.z0[i];
    len2 += dz * dz;
  }
  return len2;
}

inline BondShells find_bond_shells(const ParticleStore& p, const BondTable& bonds) {
  BondShells shells;
  const double l0 = bonds.geometry.l0;
  std::vector<long> squares;  // n of each shell
  shells.of_entry.assign(bonds.entry_count(), BondShells::kOff);
  for (std::size_t i = 0; i < bonds.particle_count(); ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const double k = reference_length2(p, i, bonds.neighbor[b]) / (l0 * l0);
      const long n = std::lround(k);
      if (n < 1 || std::abs(k - static_cast<double>(n)) > 1e-9 * static_cast<double>(n)) continue;
      std::size_t s = 0;
      while (s < squares.size() && squares[s] != n) ++s;
      if (s == squares.size()) {
        if (s == BondShells::kOff) continue;
        squares.push_back(n);
        shells.length.push_back(l0 * std::sqrt(static_cast<double>(n)));
      }
      shells.of_entry[b] = static_cast<std::uint8_t>(s);
    }
  return shells;
}

}  // namespace mpsolid
