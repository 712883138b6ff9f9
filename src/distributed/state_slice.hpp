#pragma once
// A rank's slice of a state (docs/mpi.md): its owned particles' state arrays
// (storage range `owned`), then the evolving fields of the rigid bodies and
// loads inside that range, in order, as doubles, and of every pressure load
// (which may be split: each rank holds it, with the same running step) when
// the slice carries the shared items. The whole state writes and
// reads it at the rank's global range; the rank's local state (where every
// body and load inside its owned range is its own) reads and writes it at
// its local owned range. MPI ranks send it as a message; the threads of a
// team (src/solver/thread_parts.hpp) copy it through a buffer.
#include <cstddef>
#include <vector>

#include "src/core/solver_state.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

struct StateSlice {
  // Appends the slice of `state` at `owned` to `out` (with the shared items
  // when `shared`).
  static void append(const SolverState& state, Range owned, std::vector<double>& out,
                     bool shared = true);
  // Reads a slice from in[at...] into `state` at `owned`; `at` moves past
  // it. `shared` as the slice was appended: when several slices are read
  // into one state at once (threads), only one of them carries them.
  static void read(SolverState& state, Range owned, const std::vector<double>& in, std::size_t& at,
                   bool shared = true);
  // The same without the particles: the rigid bodies' and loads' fields.
  static void append_items(const SolverState& state, Range owned, std::vector<double>& out,
                           bool shared = true);
  static void read_items(SolverState& state, Range owned, const std::vector<double>& in,
                         std::size_t& at, bool shared = true);
};

}  // namespace mpsolid
