#pragma once
// A rank's part of a case set up from the case alone (docs/mpi.md), without
// the whole state: the lattice sites of its storage range and those within a
// bond's reach of them, their bonds, its halo plan, its rigid bodies, loads,
// holds and probes, and the initial motion. It is the part local_part cuts
// from the whole set-up state (src/distributed/part_message.hpp), bit for
// bit. A rank visits every site of the case (O(N) time, a few passes of the
// lattice fill) but keeps only its own and its neighbours' (O(N / R + halo)
// memory).
#include "src/case/case_spec.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/part_message.hpp"
#include "src/distributed/rank_group.hpp"
#include "src/solver/setup.hpp"

namespace mpsolid {

// A bond's reach in the case, a hair over re (a bond joins sites closer
// than re, whatever the rounding of their positions).
double bond_reach(const CaseSpec& spec);

// Per body (laid out by `layout`, the case's), whether a cut over `ranks`
// keeps it whole on one rank: a body under a force (its share and its
// centroid sum over all of it), and a rigid body no larger than a tenth of
// a rank's share of the particles.
// A larger rigid body kept whole could unbalance the ranks by more than
// that, so the cut may split it (src/solver/split_rigid_bodies.hpp), for
// the price of an all-gather of its projection's chunk sums each step.
std::vector<bool> bodies_kept_whole(const CaseSpec& spec, const BodyLayout& layout, int ranks);

// The case's cut over `ranks` from its particle count alone (no rank holds
// the bond table to weigh them by), the bodies bodies_kept_whole names
// kept whole.
Decomposition decompose_case(const CaseSpec& spec, int ranks);

// Rank `rank`'s part of the case cut by `d`, its loads not yet scheduled
// (schedule_loads, once dt is fixed). With contact every rank of `world`
// calls it together: each finds the contact candidates among its own
// particles and the ranks share them. Throws std::invalid_argument for a
// rigid or loaded body the cut splits.
LocalPart set_up_part(const CaseSpec& spec, const Decomposition& d, int rank,
                      const RankGroup* world = nullptr);

}  // namespace mpsolid
