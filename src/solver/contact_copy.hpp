#pragma once
// Rank 0's copy of the contact candidates over MPI ranks where it keeps no
// copy of the particles (docs/mpi.md): every candidate (the contacting
// bodies' outer rows), the bonds between them and a Verlet list of its
// own. A check's round brings the moving candidates' positions from their
// owners; then the contact energy, the closest pair and the
// interpenetration check read the copy as a one-rank run reads the whole
// state, with its bits: a candidate's pairs are the whole state's, in the
// same ascending order, and no figure depends on when a list was built.
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/contact_state.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/solver_state.hpp"
#include "src/distributed/local_state.hpp"

namespace mpsolid {

struct ContactCopy {
  ParticleStore particles;                   // the candidates, in storage order
  BondTable bonds;                           // the bonds between them
  std::vector<std::uint32_t> storage_index;  // each one's global storage index
};

// The copy from a part that holds every candidate (any rank's, as set up),
// and `contact` over it: candidate a is the copy's particle a, its list
// built.
ContactCopy copy_contact_candidates(const SolverState& local, const LocalLayout& layout,
                                    ContactState& contact);

// The moving candidates' positions (x, y[, z] each, in candidate order), as
// a check's round brings them, into the copy.
void place_moving_candidates(ContactCopy& copy, const ContactState& contact,
                             const std::vector<double>& positions);

}  // namespace mpsolid
