#pragma once
// A per-particle field somewhere in memory, described for code that copies
// particles' values without knowing who owns the array (the halo exchanges,
// docs/mpi.md): `width` values per particle, value c of particle i at
// data[i * particle_stride + c * component_stride]. A ParticleStore array is
// {data, 1, 1, 0}; rows of four per particle {data, 4, 4, 1}; four component
// arrays of n values {data, 4, 1, n}.
#include <cstddef>
#include <initializer_list>
#include <vector>

namespace mpsolid {

struct ParticleField {
  double* data = nullptr;
  std::size_t width = 1;
  std::size_t particle_stride = 1;
  std::size_t component_stride = 0;

  double& at(std::size_t i, std::size_t c) const {
    return data[i * particle_stride + c * component_stride];
  }
};

inline ParticleField field_of(std::vector<double>& values) {
  return {values.data(), 1, 1, 0};
}

// A halo that carries nothing: the step on one rank, where every partner
// is this process's own. Every halo is called as halo(name, fields), or in
// two halves, post(name, fields) then finish(), so that work that needs no
// ghost runs while the values travel.
struct NoHalo {
  void operator()(const char*, std::initializer_list<ParticleField>) const {}
  void post(const char*, std::initializer_list<ParticleField>) const {}
  void finish() const {}
};

}  // namespace mpsolid
