#pragma once
// A rank's halo in local indices (docs/mpi.md): per peer, which of its
// particles it sends and where what it receives goes, with the message
// buffers kept from step to step, and the exchange that gives the ghosts
// their owners' values of any per-particle fields.
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "src/core/particle_field.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/rank_group.hpp"

namespace mpsolid {

struct LocalHalo {
  std::vector<int> peers;
  std::vector<std::vector<std::uint32_t>> send, receive;  // local indices, per peer
  std::vector<std::vector<double>> out, in;               // the messages, reused
  std::vector<ParticleField> posted;                      // a posted exchange's fields
};
// The halo plan (global indices) in the layout's local indices.
LocalHalo local_halo(const HaloPlan& plan, const LocalLayout& layout);

// What crossed to this rank from the others through one named halo (or
// collective call), summed over its calls: the values received, and the
// 64-byte lines they fill (each message counted from a line of its own, as
// the threads' mailboxes place them: src/distributed/thread_ranks.hpp).
struct HaloTally {
  const char* name = "";
  double calls = 0;
  double bytes = 0;
  double lines = 0;
  // Counts one message of `message_bytes` received.
  void received(std::size_t message_bytes);
};

// What the halos cost this rank: wall time in exchanges, bytes sent, and
// what each named halo brought in.
struct HaloCost {
  double seconds = 0;
  double bytes_sent = 0;
  std::vector<HaloTally> tallies;  // in the order of their first calls

  // Counts one call of halo `name` (a string literal); its messages follow.
  HaloTally& tally(const char* name);
};

// Adds the wall time of its scope (communication) to a halo cost.
class CommunicationTime {
 public:
  explicit CommunicationTime(HaloCost& cost)
      : cost_(cost), start_(std::chrono::steady_clock::now()) {}
  ~CommunicationTime() {
    cost_.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  CommunicationTime(const CommunicationTime&) = delete;
  CommunicationTime& operator=(const CommunicationTime&) = delete;

 private:
  HaloCost& cost_;
  std::chrono::steady_clock::time_point start_;
};

// Gives the ghosts their owners' values of the given fields, tallied under
// `name`. Collective over the halo's peers.
void exchange_halo(const RankGroup& world, LocalHalo& halo, const char* name,
                   std::initializer_list<ParticleField> fields, HaloCost& cost);
// The same in two halves where the ranks can split it (RankGroup::posts):
// post_halo sends the owned values (the whole exchange where they cannot);
// finish_halo gives the ghosts theirs (nothing when none is posted). The
// owned values of the fields must not change between the two.
void post_halo(const RankGroup& world, LocalHalo& halo, const char* name,
               std::initializer_list<ParticleField> fields, HaloCost& cost);
void finish_halo(const RankGroup& world, LocalHalo& halo, HaloCost& cost);

}  // namespace mpsolid
