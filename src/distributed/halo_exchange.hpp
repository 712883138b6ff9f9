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
#include "src/distributed/communicator.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/local_state.hpp"

namespace mpsolid {

struct LocalHalo {
  std::vector<int> peers;
  std::vector<std::vector<std::uint32_t>> send, receive;  // local indices, per peer
  std::vector<std::vector<double>> out, in;               // the messages, reused
};
// The halo plan (global indices) in the layout's local indices.
LocalHalo local_halo(const HaloPlan& plan, const LocalLayout& layout);

// What the halos cost this rank: wall time in exchanges, bytes sent.
struct HaloCost {
  double seconds = 0;
  double bytes_sent = 0;
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

// Gives the ghosts their owners' values of the given fields. Collective
// over the halo's peers.
void exchange_halo(const Communicator& world, LocalHalo& halo,
                   std::initializer_list<ParticleField> fields, HaloCost& cost);

}  // namespace mpsolid
