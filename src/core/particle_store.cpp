#include "src/core/particle_store.hpp"

namespace mpsolid {

const char* kind_name(Kind kind) {
  switch (kind) {
    case Kind::wall:
      return "wall";
    case Kind::elastic:
      return "elastic";
    case Kind::rigid:
      return "rigid";
  }
  return "unknown";
}

void ParticleStore::resize(std::size_t n) {
  for (auto* v : {&x, &y, &vx, &vy, &theta, &omega, &x0, &y0, &strain, &pressure, &fx, &fy, &torque,
                  &inv_mass, &inv_inertia, &lambda, &mu})
    v->assign(n, 0.0);
  half_cos.assign(n, 1.0);
  half_sin.assign(n, 0.0);
  id.assign(n, 0);
  body.assign(n, 0);
  material.assign(n, 0);
  kind.assign(n, Kind::elastic);
}

std::vector<std::size_t> ParticleStore::storage_of_id() const {
  std::vector<std::size_t> storage(size());
  for (std::size_t i = 0; i < size(); ++i) storage[static_cast<std::size_t>(id[i])] = i;
  return storage;
}

}  // namespace mpsolid
