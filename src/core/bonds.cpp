#include "src/core/bonds.hpp"

#include <cmath>
#include <cstring>

#include "kernels/bond_math.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid {

double lattice_number_density(double l0, double re) {
  double n0 = 0.0;
  const int reach = static_cast<int>(std::ceil(re / l0));
  for (int a = -reach; a <= reach; ++a)
    for (int b = -reach; b <= reach; ++b) {
      const double r = l0 * std::sqrt(static_cast<double>(a * a + b * b));
      n0 += bond_math::weight(r, re);
    }
  return n0;
}

KernelConstants kernel_constants(double l0, double depth) {
  KernelConstants k;
  k.l0 = l0;
  k.re = kRadiusOverSpacing * l0;
  k.n0 = lattice_number_density(l0, k.re);
  k.volume = l0 * l0 * depth;
  return k;
}

BondTable make_bond_table(const ParticleStore& p, const NeighborLists& lists,
                          const KernelConstants& constants) {
  BondTable t;
  t.constants = constants;
  t.offsets = lists.offsets;
  t.neighbor = lists.indices;
  const std::size_t m = t.neighbor.size();
  for (auto* v : {&t.r0x, &t.r0y, &t.strain_coef, &t.spring_coef}) v->resize(m);
  const double d_over_n0 = kDim / constants.n0;
  parallel_for(0, p.size(), [&](std::size_t i) {
    for (std::uint32_t b = t.begin(i); b < t.end(i); ++b) {
      const std::size_t j = t.neighbor[b];
      const double r0x = p.x0[j] - p.x0[i];
      const double r0y = p.y0[j] - p.y0[i];
      const double len = std::sqrt(r0x * r0x + r0y * r0y);
      const double w0 = bond_math::weight(len, constants.re);
      const double mu_ij = 0.5 * (p.mu[i] + p.mu[j]);
      t.r0x[b] = r0x;
      t.r0y[b] = r0y;
      t.strain_coef[b] = d_over_n0 * w0 / len;
      t.spring_coef[b] = constants.volume * d_over_n0 * 4.0 * mu_ij * w0 / (len * len);
    }
  });
  return t;
}

BondTable build_bonds(const ParticleStore& particles, const KernelConstants& constants,
                      NeighborMethod method) {
  return make_bond_table(
      particles, find_neighbors(particles.x0, particles.y0, constants.re, method), constants);
}

std::uint64_t BondTable::hash() const {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < bytes; ++k) h = (h ^ c[k]) * 1099511628211ull;
  };
  mix(offsets.data(), offsets.size() * sizeof(offsets[0]));
  mix(neighbor.data(), neighbor.size() * sizeof(neighbor[0]));
  mix(r0x.data(), r0x.size() * sizeof(double));
  mix(r0y.data(), r0y.size() * sizeof(double));
  mix(spring_coef.data(), spring_coef.size() * sizeof(double));
  return h;
}

}  // namespace mpsolid
