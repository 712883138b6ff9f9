#pragma once
// A test oracle: the gather over one particle's bonds from its own end, for
// the rotation-based models (the product computes each bond once, into its
// slot: kernels/bond_slots.hpp): visit(b, j, bond_vectors, 1 / |r_ij|) for
// each bond b = (i, j) in the fixed CSR order.
#include <cmath>

#include "kernels/bond_math.hpp"
#include "src/core/bonds.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

template <class Visit>
inline void for_each_bond(const ParticleStore& p, const BondTable& bonds, std::size_t i,
                          Visit&& visit) {
  const double xi = p.x[i], yi = p.y[i], ci = p.half_cos[i], si = p.half_sin[i];
  const std::uint32_t last = bonds.end(i);
  for (std::uint32_t b = bonds.begin(i); b < last; ++b) {
    const std::size_t j = bonds.neighbor[b];
    const auto rot = bond_math::bond_rotation(ci, si, p.half_cos[j], p.half_sin[j]);
    const auto v = bond_math::bond_vectors(xi, yi, p.x[j], p.y[j], rot, bonds.r0x[b], bonds.r0y[b]);
    const double inv_len = 1.0 / std::sqrt(v.rx * v.rx + v.ry * v.ry);
    visit(b, j, v, inv_len);
  }
}

}  // namespace mpsolid
