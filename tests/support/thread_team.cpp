#include "tests/support/thread_team.hpp"

#include "src/core/parallel.hpp"
#include "src/distributed/thread_ranks.hpp"

namespace mpsolid::testing {

void as_ranks(int ranks, const std::function<void(const RankGroup&, int)>& f) {
  const int threads_before = thread_count();
  set_thread_count(ranks);
  ThreadMailboxes boxes(ranks);
  run_in_team([&] {
    const auto me = static_cast<int>(team_rank());
    serial_section([&] { f(ThreadRanks(boxes, me), me); });
  });
  set_thread_count(threads_before);
}

}  // namespace mpsolid::testing
