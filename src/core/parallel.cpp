#include "src/core/parallel.hpp"

#include <omp.h>

#include "src/core/float_mode.hpp"

namespace mpsolid {

void set_thread_count(int threads) {
  omp_set_num_threads(threads > 0 ? threads : 1);
}
int thread_count() {
  return omp_get_max_threads();
}
int available_cores() {
  return omp_get_num_procs();
}

namespace detail {
thread_local TeamSlot team_slot;

void fork_join_blocks(std::size_t begin, std::size_t end,
                      void (*block)(void*, std::size_t, std::size_t), void* context) {
  const std::size_t count = end - begin;
  // Below this size the team wake-up costs more than the work.
  constexpr std::size_t kMinPerThread = 128;
  const int threads = omp_get_max_threads();
  SubnormalModeScope mode;
  if (threads == 1 || count < 2 * kMinPerThread || omp_in_parallel()) {
    block(context, begin, end);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    SubnormalModeScope thread_mode;
    const Range r = static_block(begin, end, static_cast<std::size_t>(omp_get_thread_num()),
                                 static_cast<std::size_t>(omp_get_num_threads()));
    if (r.begin < r.end) block(context, r.begin, r.end);
  }
}

void run_team(void (*body)(void*), void* context) {
  const int threads = omp_get_max_threads();
  SubnormalModeScope mode;
  if (threads == 1 || omp_in_parallel()) {
    body(context);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    SubnormalModeScope thread_mode;
    team_slot = {static_cast<std::size_t>(omp_get_thread_num()),
                 static_cast<std::size_t>(omp_get_num_threads())};
    body(context);
    team_slot = {};
  }
}

void team_barrier() {
#pragma omp barrier
}
}  // namespace detail

}  // namespace mpsolid
