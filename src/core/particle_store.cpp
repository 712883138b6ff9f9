#include "src/core/particle_store.hpp"

#include <stdexcept>

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

const char* role_name(ArrayRole role) {
  switch (role) {
    case ArrayRole::state:
      return "state";
    case ArrayRole::reference:
      return "reference";
    case ArrayRole::work:
      return "work";
    case ArrayRole::constant:
      return "constant";
  }
  return "unknown";
}

const std::vector<StateArray>& state_arrays(int dimension) {
  static const auto of = [](int d) {
    std::vector<StateArray> out;
    for (const StateArray& a : kStateArrays)
      if (present_in(a.dims, d)) out.push_back(a);
    return out;
  };
  static const std::vector<StateArray> plane = of(2), space = of(3);
  return dimension == 3 ? space : plane;
}

void ParticleStore::resize(std::size_t n) {
  for_each_particle_array(*this, [n](const auto& info, auto& v) { v.assign(n, info.initial); });
}

void ParticleStore::set_kind_ranges(std::size_t end) {
  const auto first_not = [&](std::size_t from, Kind k) {
    while (from < end && kind[from] == k) ++from;
    return from;
  };
  const std::size_t walls_end = first_not(0, Kind::wall);
  const std::size_t elastic_end = first_not(walls_end, Kind::elastic);
  walls = {0, walls_end};
  elastic = {walls_end, elastic_end};
  rigid = {elastic_end, first_not(elastic_end, Kind::rigid)};
  if (rigid.end != end) throw std::logic_error("set_kind_ranges: kinds are not grouped in storage");
}

std::vector<std::size_t> ParticleStore::storage_of_id() const {
  std::vector<std::size_t> storage(size());
  for (std::size_t i = 0; i < size(); ++i) storage[static_cast<std::size_t>(id[i])] = i;
  return storage;
}

}  // namespace mpsolid
