#pragma once
// Contact over ranks (docs/mpi.md). Every rank holds every candidate of the
// run (the bodies' outer rows: a small part of the particles) and builds the
// Verlet list over all of them; it computes the contact forces of its own
// moving candidates. Their partners' current positions arrive each step
// through the bond halo (bond ghosts) or through the contact halo: the
// partners its list holds that it neither owns nor gets through the bond
// halo (walls never move), planned again with every rebuild.
//
// Every rank rebuilds when any rank finds one of its own candidates moved
// past half the skin since the last build (a partner is checked by its
// owner, and all built at the same positions): then no pair closer than d
// is missing from any list, and each candidate sums its pairs closer than d
// in ascending partner order, as the serial pass does: the same bits.
#include <cstdint>
#include <vector>

#include "src/core/solver_state.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/halo_exchange.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/rank_group.hpp"

namespace mpsolid {

struct RankContact {
  Decomposition decomposition;  // who owns a partner
  // Every rank's moving candidates, as runs of candidate indices in
  // candidate order (one run per owned piece at most; with slabs, each
  // rank one run and the ranks' in rank order), the same on every rank.
  std::vector<std::vector<Range>> moving_by_rank;
  int rank = -1;                           // this part's (-1: it owns no particle)
  std::vector<std::uint32_t> bond_ghosts;  // local indices the bond halo refreshes, ascending
  LocalHalo halo;                          // the contact halo, planned at each rebuild
  // This rank's runs.
  const std::vector<Range>& owned() const {
    static const std::vector<Range> none;
    return rank < 0 ? none : moving_by_rank[static_cast<std::size_t>(rank)];
  }
};

// Values `width` per moving candidate, every rank's own in rank order (a
// gather's), put in candidate order: moving candidate a's at
// width * (a - first moving).
std::vector<double> in_candidate_order(const RankContact& rc, const std::vector<double>& by_rank,
                                       std::size_t width);

// The contact part of a rank's local state `s` (whose contact holds every
// candidate of the run); `bond_halo` is the rank's halo for the bonds.
RankContact make_rank_contact(const SolverState& s, const LocalLayout& layout,
                              const Decomposition& d, const LocalHalo& bond_halo);

// Every rank together: every moving candidate's current position to every
// rank, the list rebuilt and the contact halo planned from it. The owned
// and bond-ghost positions must be current.
void rebuild_rank_contact(RankContact& rc, SolverState& s, const LocalLayout& layout,
                          const RankGroup& world, HaloCost& cost);

// The contact pass of step `step` (after the bond halo's positions): the
// contact halo's positions, this rank's candidates' forces, and when any
// rank's list went stale a rebuild on every rank and the pass again.
void rank_contact_pass(RankContact& rc, SolverState& s, const LocalLayout& layout,
                       const RankGroup& world, std::int64_t step, HaloCost& cost);

}  // namespace mpsolid
