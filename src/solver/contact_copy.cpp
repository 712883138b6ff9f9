#include "src/solver/contact_copy.hpp"

#include <numeric>
#include <stdexcept>

#include "neighbor/bond_search.hpp"
#include "neighbor/contact_search.hpp"

namespace mpsolid {

ContactCopy copy_contact_candidates(const SolverState& local, const LocalLayout& layout,
                                    ContactState& contact) {
  const ContactState& c = local.contact;
  ContactCopy copy;
  LocalLayout candidates;  // the part's candidates, picked from its particles
  candidates.global_of = c.candidates;
  copy.particles = local_particles(local.particles, candidates);
  // Bonds join particles closer than re in the reference configuration: the
  // copy's are those of the whole table between candidates.
  copy.bonds = build_bonds(copy.particles, local.bonds.geometry);
  for (const std::uint32_t i : c.candidates) copy.storage_index.push_back(layout.global_of[i]);
  contact = ContactState{};
  contact.parameters = c.parameters;
  contact.candidates.resize(c.size());
  std::iota(contact.candidates.begin(), contact.candidates.end(), 0u);
  contact.group = c.group;
  contact.first_moving = c.first_moving;
  contact.zero_forces(copy.particles.dimension);
  build_contact_list(contact, copy.particles, copy.bonds);
  return copy;
}

void place_moving_candidates(ContactCopy& copy, const ContactState& contact,
                             const std::vector<double>& positions) {
  ParticleStore& p = copy.particles;
  const std::size_t axes = p.dimension == 3 ? 3 : 2;
  if (positions.size() != axes * (contact.size() - contact.first_moving))
    throw std::logic_error("contact: the ranks' candidates do not cover the moving ones");
  for (std::size_t a = contact.first_moving, at = 0; a < contact.size(); ++a) {
    p.x[a] = positions[at++];
    p.y[a] = positions[at++];
    if (axes == 3) p.z[a] = positions[at++];
  }
}

}  // namespace mpsolid
