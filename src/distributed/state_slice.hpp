#pragma once
// A rank's slice of a state (docs/mpi.md): its owned particles' state arrays
// (storage range `owned`), then the evolving fields of the rigid bodies and
// loads inside that range, in order, as doubles. The whole state writes and
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
  // Appends the slice of `state` at `owned` to `out`.
  static void append(const SolverState& state, Range owned, std::vector<double>& out);
  // Reads a slice from in[at...] into `state` at `owned`; `at` moves past it.
  static void read(SolverState& state, Range owned, const std::vector<double>& in, std::size_t& at);
};

}  // namespace mpsolid
