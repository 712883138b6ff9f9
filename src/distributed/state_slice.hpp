#pragma once
// A rank's slice of a state (docs/mpi.md): its owned particles' state arrays
// (storage ranges `owned`: a slab's one, or a cut's pieces), then the evolving fields of the rigid
// bodies with particles there (a rigid body split between ranks: each of its ranks carries its
// pose) and loads inside that range, in order, as doubles, and of every pressure load (which may
// be split: each rank holds it, with the same running step) when the slice carries the shared
// items. The whole state writes and reads it at the rank's global range; the rank's local state
// (where every body and load inside its owned range is its own) reads and writes it at its local
// owned range. MPI ranks send it as a message; the threads of a team (src/solver/thread_parts.hpp)
// copy it through a buffer.
#include <cstddef>
#include <vector>

#include "src/core/solver_state.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

struct StateSlice {
  // The same at one range (a rank's local owned range, or a slab).
  static void append(const SolverState& state, Range owned, std::vector<double>& out,
                     bool shared = true) {
    append(state, std::vector<Range>{owned}, out, shared);
  }
  static void read(SolverState& state, Range owned, const std::vector<double>& in, std::size_t& at,
                   bool shared = true) {
    read(state, std::vector<Range>{owned}, in, at, shared);
  }
  static void append_items(const SolverState& state, Range owned, std::vector<double>& out,
                           bool shared = true) {
    append_items(state, std::vector<Range>{owned}, out, shared);
  }
  static void read_items(SolverState& state, Range owned, const std::vector<double>& in,
                         std::size_t& at, bool shared = true) {
    read_items(state, std::vector<Range>{owned}, in, at, shared);
  }

  // Appends the slice of `state` at `owned` to `out` (with the shared items
  // when `shared`).
  static void append(const SolverState& state, const std::vector<Range>& owned,
                     std::vector<double>& out, bool shared = true);
  // Reads a slice from in[at...] into `state` at `owned`; `at` moves past
  // it. `shared` as the slice was appended: when several slices are read
  // into one state at once (threads), only one of them carries them.
  static void read(SolverState& state, const std::vector<Range>& owned,
                   const std::vector<double>& in, std::size_t& at, bool shared = true);
  // The same without the particles: the rigid bodies' and loads' fields.
  static void append_items(const SolverState& state, const std::vector<Range>& owned,
                           std::vector<double>& out, bool shared = true);
  static void read_items(SolverState& state, const std::vector<Range>& owned,
                         const std::vector<double>& in, std::size_t& at, bool shared = true);
};

}  // namespace mpsolid
