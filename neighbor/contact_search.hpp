#pragma once
// The contact search (MODEL.md section 8): pairs of contact candidates that
// may touch (not bonded in the reference configuration, not in one group of
// particles that never move relative to each other) within a cutoff, found
// by the cell list on the current positions.
#include <cstddef>

#include "src/core/bonds.hpp"
#include "src/core/contact_state.hpp"

namespace mpsolid {

// Rebuilds the Verlet list from the candidates' current positions: every
// pair closer than d + skin, from both ends, partners ascending. Serial and
// in a fixed order.
void build_contact_list(ContactState& contact, const ParticleStore& p, const BondTable& bonds);

// Rebuilds the list if it is not valid for the current positions (serial).
void refresh_contact_list(ContactState& contact, const ParticleStore& p, const BondTable& bonds);

// The closest pair of candidates that may touch, from a search of its own
// (independent of the Verlet list and of when it was built).
struct ClosestContact {
  bool found = false;  // a pair closer than the cutoff exists
  double distance = 0;
  std::size_t i = 0, j = 0;  // storage indices, i < j
};
ClosestContact closest_contact(const ContactState& contact, const ParticleStore& p,
                               const BondTable& bonds, double cutoff);

}  // namespace mpsolid
