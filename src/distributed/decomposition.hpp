#pragma once
// Which rank owns which particles, and the halo each rank needs (docs/mpi.md).
//
// A rank owns a contiguous range of storage indices, cut anywhere: the
// global sums take each rank's share of the serial chunks
// (src/distributed/ordered_sum_parts.hpp), which gives the serial bits at
// any cut. The ranges are balanced by work (bond entries plus particles).
// Storage is row by row within each body, so a range is a slab of rows.
//
// A rank's ghosts are the particles its owned particles are bonded to and
// it does not own: the gathers of an owned particle read only its own
// bonds' partners, so one layer of ghosts, refreshed before each pass that
// reads neighbours, gives every owned particle the serial inputs.
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

struct Decomposition {
  std::vector<std::size_t> starts;  // rank r owns [starts[r], starts[r + 1])

  int ranks() const { return static_cast<int>(starts.size()) - 1; }
  Range owned(int rank) const {
    return {starts[static_cast<std::size_t>(rank)], starts[static_cast<std::size_t>(rank) + 1]};
  }
  int owner_of(std::size_t i) const;
};

// Contiguous ranges over the bond table's particles for `ranks` ranks,
// balanced by bond entries + particles to within a particle's work. A rank
// may own nothing when there are fewer particles than ranks, or when a body
// kept whole holds several ranks' shares. No cut falls inside a range of
// `keep_whole` (rigid and loaded bodies, whose sums run over all their
// particles): such a cut moves down to the range's start.
Decomposition decompose(const BondTable& bonds, int ranks,
                        const std::vector<Range>& keep_whole = {});

// Each particle's work as decompose counts it: its bond entries plus one.
std::vector<double> particle_work(const BondTable& bonds);
// The same cut over given per-particle costs (decompose: particle_work; the
// threads as ranks re-cut by what each thread measured).
Decomposition decompose_costs(const std::vector<double>& cost, int ranks,
                              const std::vector<Range>& keep_whole = {});

// The same cut with every particle's work one: from the particle count
// alone, for a set-up by part, where no rank holds the bond table.
Decomposition decompose_count(std::size_t particles, int ranks,
                              const std::vector<Range>& keep_whole = {});

// One rank's halo: its ghosts, and per neighbouring rank what it sends
// (its own particles that rank needs) and receives (that rank's particles
// it needs). All storage indices, ascending; neighbours ascending.
struct HaloPlan {
  std::vector<std::uint32_t> ghosts;
  std::vector<int> peers;
  std::vector<std::vector<std::uint32_t>> send, receive;  // per peer
};

HaloPlan plan_halo(const BondTable& bonds, const Decomposition& d, int rank);

}  // namespace mpsolid
