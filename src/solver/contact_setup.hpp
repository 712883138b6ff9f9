#pragma once
// Contact at set-up (MODEL.md section 8): which particles are candidates,
// their groups, the parameters in SI units, and the contact term of the
// stable-step bound.
#include <algorithm>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/contact_state.hpp"
#include "src/core/solver_state.hpp"

namespace mpsolid {

// The candidates are the surface particles of the case's contacting bodies:
// those with fewer same-body bonds than a lattice interior particle has (the
// outer two rows, since bonds reach 2.1 l0). The list is built at once.
// Empty (disabled) when the case has no contact.
ContactState make_contact(const CaseSpec& spec, const SolverState& s);

// The candidates among the particles `rows` of `s`, whose bond rows must be
// whole, in storage order: their indices and groups appended.
struct CandidateList {
  std::vector<std::uint32_t> index;
  std::vector<std::int32_t> group;
};
void find_contact_candidates(const CaseSpec& spec, const SolverState& s, Range rows,
                             CandidateList& out);

// The contact of the case over `candidates` (indices into `p`, ascending):
// its parameters, groups and forces, without a list yet.
ContactState contact_over(const CaseSpec& spec, const ParticleStore& p, CandidateList candidates);

// A bound on the squared angular frequency contact adds to the system:
// 2 z k / m, with z the most lattice sites closer than d to any point and m
// the lightest candidate that moves (Gershgorin's bound on the pair
// stiffness, whose tangential part stays below k while pairs are farther
// apart than d / 2, which the interpenetration check keeps), from the
// largest inverse mass among the candidates' bodies. 0 without contact.
double contact_omega_squared(const CaseSpec& spec, double largest_inv_mass);
// That inverse mass among the particles `held` (global storage indices,
// the first at index `first` of `p`) of the contact's moving bodies (their
// global storage ranges `body_ranges`); the largest over every part is the
// whole state's.
double largest_contact_inv_mass(const CaseSpec& spec, const std::vector<Range>& body_ranges,
                                const ParticleStore& p, Range held, std::size_t first);

// How far the closest-pair diagnostic looks: d + skin, and at least 3 l0.
// (Within a body, surface pairs sqrt 5 l0 apart at rest are not bonded: the
// column reads 2.24 l0 at rest and shows a gap between bodies only once it
// is smaller.)
inline double contact_search_reach(const CaseSpec& spec) {
  return std::max(spec.contact.distance + spec.contact.skin, 3.0) * spec.l0;
}

}  // namespace mpsolid
