#pragma once
// A rank's own copy of the particles and bonds (docs/mpi.md): its owned
// particles and their ghosts, in global storage order, so every owned
// particle's bond row lists the same partners in the same order as the
// serial table's and its gathers add the same terms in the same order.
// Owned rows are whole; a ghost's row holds only its bonds to owned
// particles (what the owned particles' bond terms need). A ghost's own
// per-particle results come from its owner through the halo, never from
// its partial row.
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/solver_state.hpp"
#include "src/distributed/decomposition.hpp"

namespace mpsolid {

struct LocalLayout {
  std::vector<std::uint32_t> global_of;  // local index -> global storage index, ascending
  Range owned;                           // the owned particles' local range
  Range owned_global;                    // ... and their global storage range

  std::size_t size() const { return global_of.size(); }
  // The local index of an owned particle's global storage index (owned
  // particles are contiguous in both: a shift).
  std::size_t local_of_owned(std::size_t global) const {
    return owned.begin + (global - owned_global.begin);
  }
  // The local index of a global storage index this rank holds.
  std::size_t local_of(std::uint32_t global) const;
  // The same, or -1 when this rank does not hold it.
  std::int64_t find(std::size_t global) const;
};

// Owned particles and ghosts, merged in global order, with the particles of
// `also` (global storage indices, ascending: every contact candidate of the
// run) that are neither.
LocalLayout local_layout(const Decomposition& d, const HaloPlan& halo, int rank,
                         const std::vector<std::uint32_t>& also = {});

// The layout's particles, every array copied, the kind ranges recomputed
// (storage is grouped by kind, and the global order is kept).
ParticleStore local_particles(const ParticleStore& global, const LocalLayout& layout);

// The layout's bond table in local indices: whole rows for owned
// particles, bonds to owned particles for ghosts; reference vectors from
// the local particles' x0, y0 (the same bits as the global table's).
BondTable local_bonds(const BondTable& global, const ParticleStore& local,
                      const LocalLayout& layout);

// The whole local solver state: particles, bonds, and the rigid bodies,
// loads and holds of the owned particles in local indices. A rigid body or
// a loaded body must be owned by one rank (its projection and its load's
// share sum over all of it); one split between ranks is refused
// (std::invalid_argument). Contact: every candidate of the run, in local
// indices (the layout must hold them all), with no list yet.
SolverState local_solver_state(const SolverState& global, const LocalLayout& layout);

}  // namespace mpsolid
