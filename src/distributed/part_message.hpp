#pragma once
// A rank's part of a run as one message (docs/mpi.md): rank 0 sets the case
// up, cuts it, and sends every other rank only what that rank steps (its
// particles and ghosts, their bonds, its bodies, loads and holds, every
// contact candidate, its halo), so a follower never holds the whole state.
// All values travel as doubles: indices and counts below 2^53 are exact.
// An empty first piece is no part: rank 0 refused the case.
#include <cstddef>
#include <functional>
#include <vector>

#include "src/core/solver_state.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/halo_exchange.hpp"
#include "src/distributed/local_state.hpp"

namespace mpsolid {

struct LocalPart {
  Decomposition decomposition;
  LocalLayout layout;
  LocalHalo halo;     // in local indices (no buffers)
  SolverState state;  // local_solver_state: no body ranges or probes
  // The run's first moving particle (global storage index): where the
  // motion sums' chunks start. Every body's range and every probe, in
  // global storage indices: what a history row reads.
  std::size_t moving_begin = 0;
  std::vector<Range> body_ranges;
  std::vector<std::size_t> probes;
};

// The part of `rank` in the set-up state `global`, cut by `d`, with every
// contact candidate of the run among its particles. Throws
// std::invalid_argument for a rigid or loaded body split between ranks.
LocalPart local_part(const SolverState& global, const Decomposition& d, int rank);

// The part as a stream of messages of at most kPartPieceValues doubles
// each (the last may be empty), so neither side ever holds the whole
// message: `send` takes each piece in order, `receive` gives the next.
inline constexpr std::size_t kPartPieceValues = std::size_t{1} << 20;  // 8 MiB
void pack_local_part(const LocalPart& part,
                     const std::function<void(const std::vector<double>&)>& send);
LocalPart unpack_local_part(const std::function<std::vector<double>()>& receive);

// A rank's own rigid bodies and loads, whole, with their ranges in global
// storage indices (the owned particles are contiguous in both), appended to
// `out`: what rank 0 keeps of them when it holds no particle. Pressure
// loads are left out: every part holds each whole.
void append_owned_items(const SolverState& local, const LocalLayout& layout,
                        std::vector<double>& out);
// Reads them from in[at...] onto `head`'s rigid bodies and loads; `at` moves
// past them.
void read_owned_items(const std::vector<double>& in, std::size_t& at, SolverState& head);
// Each rigid body of `head` once (a body split between ranks comes from each
// of its ranks, over its own particles), over its whole storage range (body
// k of `body_names` is head.body_ranges[k]), in storage order, without its
// particles' offsets: rank 0 keeps a body's pose and make-up, and places no
// particle.
void merge_rigid_bodies(SolverState& head, const std::vector<std::string>& body_names);

}  // namespace mpsolid
