#pragma once
// The threads of one team as ranks, for tests that run collective code in
// one process (src/distributed/thread_ranks.hpp).
#include <functional>

#include "src/distributed/rank_group.hpp"

namespace mpsolid::testing {

// Calls f(world, rank) on every one of `ranks` ranks together (threads as
// ranks), then goes back to the thread count before.
void as_ranks(int ranks, const std::function<void(const RankGroup&, int)>& f);

}  // namespace mpsolid::testing
