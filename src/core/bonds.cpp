#include "src/core/bonds.hpp"

#include <utility>

#include "src/core/hash.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid {

BondGeometry bond_geometry(double l0, double depth) {
  return {l0, kRadiusOverSpacing * l0, l0 * l0 * depth};
}

BondGeometry bond_geometry_3d(double l0) {
  return {l0, kRadiusOverSpacing * l0, l0 * l0 * l0, 3};
}

BondTable make_bond_table(const ParticleStore& p, std::vector<std::uint32_t> offsets,
                          std::vector<std::uint32_t> neighbor, const BondGeometry& geometry) {
  BondTable t;
  t.geometry = geometry;
  t.offsets = std::move(offsets);
  t.neighbor = std::move(neighbor);
  t.r0x.resize(t.neighbor.size());
  t.r0y.resize(t.neighbor.size());
  const bool space = p.dimension == 3;
  if (space) t.r0z.resize(t.neighbor.size());
  parallel_for(0, p.size(), [&](std::size_t i) {
    for (std::uint32_t b = t.begin(i); b < t.end(i); ++b) {
      const std::size_t j = t.neighbor[b];
      t.r0x[b] = p.x0[j] - p.x0[i];
      t.r0y[b] = p.y0[j] - p.y0[i];
      if (space) t.r0z[b] = p.z0[j] - p.z0[i];
    }
  });
  return t;
}

std::uint64_t BondTable::hash() const {
  Fnv1a h;
  h.add(offsets);
  h.add(neighbor);
  h.add(r0x);
  h.add(r0y);
  if (!r0z.empty()) h.add(r0z);  // the plane's hash as it always was
  return h.value();
}

}  // namespace mpsolid
