// The decomposition over ranks (docs/mpi.md), checked in one process:
// contiguous chunk-aligned ranges that cover every particle once and balance
// the work, and halo plans in which every rank's ghosts are exactly the
// partners it does not own, and what one rank sends another is what the
// other expects to receive.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "src/core/ordered_sum.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/solver/setup.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

BondTable rod_bonds(const std::string& l0) {
  PhaseTimers timers;
  return set_up(testing::rod_case({"l0=" + l0}), timers).bonds;
}

double work_of(const BondTable& bonds, Range r) {
  return static_cast<double>(bonds.offsets[r.end] - bonds.offsets[r.begin] + r.size());
}

TEST(Decomposition, RangesAreChunkAlignedCoverEverythingAndBalanceTheWork) {
  const BondTable bonds = rod_bonds("0.0005");  // 18,080 particles: 36 chunks
  const std::size_t n = bonds.particle_count();
  const double total = work_of(bonds, {0, n});
  const double chunk_work = total / static_cast<double>((n + kSumChunk - 1) / kSumChunk);
  for (int ranks = 1; ranks <= 8; ++ranks) {
    SCOPED_TRACE(ranks);
    const Decomposition d = decompose(bonds, ranks);
    ASSERT_EQ(d.ranks(), ranks);
    EXPECT_EQ(d.starts.front(), 0u);
    EXPECT_EQ(d.starts.back(), n);
    for (int r = 0; r < ranks; ++r) {
      const Range mine = d.owned(r);
      EXPECT_LE(mine.begin, mine.end);
      if (r > 0) {
        EXPECT_EQ(mine.begin % kSumChunk, 0u);
      }
      // Within about one chunk of an equal share.
      EXPECT_NEAR(work_of(bonds, mine), total / ranks, 1.5 * chunk_work);
      for (std::size_t i = mine.begin; i < mine.end; i += 97) EXPECT_EQ(d.owner_of(i), r);
    }
  }
  // More ranks than chunks: some own nothing, every particle still has one owner.
  const BondTable small = rod_bonds("0.004");  // 300 particles, one chunk
  const Decomposition d = decompose(small, 3);
  std::size_t owned = 0;
  for (int r = 0; r < 3; ++r) owned += d.owned(r).size();
  EXPECT_EQ(owned, small.particle_count());
  for (std::size_t i = 0; i < small.particle_count(); ++i) {
    const Range r = d.owned(d.owner_of(i));
    EXPECT_TRUE(i >= r.begin && i < r.end) << i;
  }
}

TEST(Decomposition, HaloHoldsExactlyThePartnersARankDoesNotOwn) {
  const BondTable bonds = rod_bonds("0.001");
  for (int ranks : {2, 3, 5}) {
    SCOPED_TRACE(ranks);
    const Decomposition d = decompose(bonds, ranks);
    std::vector<HaloPlan> plans;
    for (int r = 0; r < ranks; ++r) plans.push_back(plan_halo(bonds, d, r));
    for (int r = 0; r < ranks; ++r) {
      const Range mine = d.owned(r);
      std::set<std::uint32_t> expected;
      for (std::size_t i = mine.begin; i < mine.end; ++i)
        for (std::uint32_t k = bonds.begin(i); k < bonds.end(i); ++k)
          if (d.owner_of(bonds.neighbor[k]) != r) expected.insert(bonds.neighbor[k]);
      const HaloPlan& plan = plans[static_cast<std::size_t>(r)];
      EXPECT_EQ(std::set<std::uint32_t>(plan.ghosts.begin(), plan.ghosts.end()), expected);
      EXPECT_TRUE(std::is_sorted(plan.ghosts.begin(), plan.ghosts.end()));
      if (ranks > 1 && !mine.empty()) {
        EXPECT_FALSE(plan.ghosts.empty());
      }
      std::size_t received = 0;
      for (std::size_t k = 0; k < plan.peers.size(); ++k) {
        const int peer = plan.peers[k];
        for (const std::uint32_t g : plan.receive[k]) EXPECT_EQ(d.owner_of(g), peer);
        received += plan.receive[k].size();
        // The peer sends exactly what this rank receives from it.
        const HaloPlan& other = plans[static_cast<std::size_t>(peer)];
        const auto at = std::find(other.peers.begin(), other.peers.end(), r);
        ASSERT_NE(at, other.peers.end());
        EXPECT_EQ(other.send[static_cast<std::size_t>(at - other.peers.begin())], plan.receive[k]);
      }
      EXPECT_EQ(received, plan.ghosts.size());
    }
  }
}

}  // namespace
}  // namespace mpsolid
