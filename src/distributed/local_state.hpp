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
  // Local index -> global storage index: the ghosts below every owned
  // particle, the owned particles, the other ghosts, each ascending (one
  // slab: all of it ascending).
  std::vector<std::uint32_t> global_of;
  Range owned;  // the owned particles' local range
  // ... and their global storage ranges (one per piece of the cut),
  // ascending, with the local index of each one's first particle.
  std::vector<Range> owned_pieces;
  std::vector<std::size_t> piece_local;

  std::size_t size() const { return global_of.size(); }
  // Sets the owned pieces (their particles are owned.begin on, in order).
  void set_owned_pieces(std::vector<Range> pieces);
  bool owns(std::size_t global) const;
  // The local index of an owned particle's global storage index.
  std::size_t local_of_owned(std::size_t global) const;
  // The local range of the owned particles of a global range (contiguous:
  // the owned particles keep their global order).
  Range owned_within(Range global) const;
  // The global range of owned particles `local` that one piece holds (an
  // item kept whole).
  Range global_of_owned(Range local) const;
  // The local index of a global storage index this rank holds.
  std::size_t local_of(std::uint32_t global) const;
  // The same, or -1 when this rank does not hold it.
  std::int64_t find(std::size_t global) const;
};

// Owned particles and ghosts (as global_of orders them), with the particles
// of `also` (global storage indices, ascending: every contact candidate of
// the run) that are neither among the ghosts.
LocalLayout local_layout(const Decomposition& d, const HaloPlan& halo, int rank,
                         const std::vector<std::uint32_t>& also = {});

// The layout's particles, every array copied, the kind ranges those of the
// owned particles (storage is grouped by kind, and the owned particles keep
// the global order; in one slab the ghosts do too, and the kind ranges
// cover them).
ParticleStore local_particles(const ParticleStore& global, const LocalLayout& layout);

// The layout's bond table in local indices: whole rows for owned
// particles, bonds to owned particles for ghosts; reference vectors from
// the local particles' x0, y0 (the same bits as the global table's).
BondTable local_bonds(const BondTable& global, const ParticleStore& local,
                      const LocalLayout& layout);

// The whole local solver state: particles, bonds, and the rigid bodies,
// loads and holds of the owned particles in local indices. A rigid body
// split between ranks is held by each of its ranks over its own particles
// (src/solver/split_rigid_bodies.hpp); a body under a force must be owned
// by one rank (its load's share sums over all of it): one split between
// ranks is refused (std::invalid_argument). Contact: every candidate of the run, in local
// indices (the layout must hold them all), with no list yet.
SolverState local_solver_state(const SolverState& global, const LocalLayout& layout);

}  // namespace mpsolid
