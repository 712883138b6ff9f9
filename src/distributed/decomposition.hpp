#pragma once
// Which rank owns which particles, and the halo each rank needs (docs/mpi.md).
//
// Storage is cut into pieces, each a contiguous range of storage indices
// owned by one rank. Slabs give each rank one piece; a cut across a body's
// rows (src/solver/part_cut.hpp) gives a rank one piece per row it crosses.
// Either way the global sums take each piece's share of the serial chunks
// (src/distributed/ordered_sum_parts.hpp), which gives the serial bits at
// any cut. Slabs are balanced by work (bond entries plus particles).
// Storage is row by row within each body, so a slab is a slab of rows.
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
  // Piece k is [starts[k], starts[k + 1]), owned by owners[k]; without
  // owners, piece r is rank r's (slabs).
  std::vector<std::size_t> starts;
  std::vector<int> owners;
  int rank_count = 0;  // with owners: the ranks (one may own no piece)

  int ranks() const { return owners.empty() ? static_cast<int>(starts.size()) - 1 : rank_count; }
  bool slabs() const { return owners.empty(); }
  std::size_t particles() const { return starts.empty() ? 0 : starts.back(); }
  // A slab's one range (a cut in pieces: std::logic_error).
  Range owned(int rank) const;
  // The rank's pieces, ascending (a slab: its one range, perhaps empty).
  std::vector<Range> pieces(int rank) const;
  // Every rank's pieces (one pass over the cut).
  std::vector<std::vector<Range>> pieces_by_rank() const;
  // The piece holding index i (the last of the empty pieces starting there).
  std::size_t piece_of(std::size_t i) const;
  int owner_of(std::size_t i) const;
  // The ranks owning some of `r`, ascending.
  std::vector<int> owners_of(Range r) const;
  bool operator==(const Decomposition&) const = default;
};

// The cut whose piece k is [starts[k], starts[k + 1]) owned by owners[k]
// over `ranks` ranks; neighbouring pieces of one rank are merged, empty
// ones dropped, and a cut that is slabs (rank r's piece r-th) is given as
// slabs.
Decomposition decomposition_in_pieces(std::vector<std::size_t> starts, std::vector<int> owners,
                                      int ranks);

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
