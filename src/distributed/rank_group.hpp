#pragma once
// The ranks a decomposed step runs over (docs/mpi.md): MPI's processes (the
// Communicator) or the threads of one team, each with its own part of the
// state (ThreadRanks, src/distributed/thread_ranks.hpp). Only what the step
// needs of them: rank and size, an all-gather in rank order, pairwise
// exchanges with neighbouring ranks and a maximum. Every call is collective
// over the ranks involved and returns the same data at any timing, so
// results never depend on message order.
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace mpsolid {

class RankGroup {
 public:
  virtual ~RankGroup() = default;

  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Every rank's values, concatenated in rank order, on every rank.
  virtual std::vector<double> all_gather(const std::vector<double>& mine) const = 0;
  // Sends out[k] to rank peers[k] and receives what peers[k] sends this
  // rank into in[k], which must already have that message's size (both
  // sides know it from the halo plan: no count is exchanged, and the
  // caller's buffers are reused from step to step). Every peer must list
  // this rank in its own call.
  virtual void exchange(const std::vector<int>& peers, const std::vector<std::vector<double>>& out,
                        std::vector<std::vector<double>>& in) const = 0;
  // The largest of every rank's value, on every rank.
  virtual std::int64_t max(std::int64_t mine) const = 0;

  // Whether an exchange can be split in two (post, then collect), so that
  // the caller works while its messages travel. Between them no other call.
  virtual bool posts() const { return false; }
  // The first half of exchange(peers, out, in): sends.
  virtual void post(const std::vector<int>&, const std::vector<std::vector<double>>&) const {
    throw std::logic_error("post: these ranks exchange in one call");
  }
  // The second half: receives into in[k] (sized as for exchange).
  virtual void collect(const std::vector<int>&, std::vector<std::vector<double>>&) const {
    throw std::logic_error("collect: these ranks exchange in one call");
  }
};

// Rank 0's `value`, on every rank (one all-gather: the others send
// nothing).
inline double from_rank_zero(const RankGroup& world, double value) {
  return world.all_gather(world.rank() == 0 ? std::vector<double>{value} : std::vector<double>{})
      .at(0);
}

}  // namespace mpsolid
