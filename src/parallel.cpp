#include "src/parallel.hpp"

#include <omp.h>

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
void parallel_blocks(std::size_t begin, std::size_t end,
                     void (*block)(void*, std::size_t, std::size_t), void* context) {
  const std::size_t count = end - begin;
  // Below this size the team wake-up costs more than the work.
  constexpr std::size_t kMinPerThread = 128;
  const int threads = omp_get_max_threads();
  if (threads == 1 || count < 2 * kMinPerThread) {
    block(context, begin, end);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    const auto rank = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t b = begin + count * rank / team;
    const std::size_t e = begin + count * (rank + 1) / team;
    if (b < e) block(context, b, e);
  }
}
}  // namespace detail

}  // namespace mpsolid
