#pragma once
// How many OpenMP threads a run uses: --threads, else OMP_NUM_THREADS (the
// usual way to set it on a cluster or in a batch job), else every core.
#include <string>

namespace mpsolid {

struct ThreadChoice {
  int threads = 1;
  std::string source;   // "--threads", "OMP_NUM_THREADS" or "all cores"
  std::string warning;  // non-empty when the count exceeds the cores
};

// `requested`: the --threads value, 0 when not given. Throws InputError for an
// OMP_NUM_THREADS that is not a whole number >= 1.
ThreadChoice choose_threads(int requested, int cores);

}  // namespace mpsolid
