// The bond slots (kernels/bond_slots.hpp): each bond has one slot that both
// of its entries point at, the runs cover every particle in order, and a
// run's pattern gives each of its particles exactly its row's slots and
// partners, so the fast path reads what the per-entry path reads.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

#include "kernels/bond_slots.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

std::vector<CaseSpec> cases() {
  return {testing::rod_case(), testing::rod_case({"l0=0.001"}),
          testing::free_block_case(12, 7, true)};
}

// The table entry of bond (i, j) in row i.
std::uint32_t entry_of(const BondTable& bonds, std::size_t i, std::size_t j) {
  for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
    if (bonds.neighbor[b] == j) return b;
  ADD_FAILURE() << "no entry (" << i << ", " << j << ")";
  return 0;
}

TEST(BondSlots, EveryBondHasOneSlotSharedByItsTwoEntries) {
  for (const CaseSpec& spec : cases()) {
    Simulation sim(spec);
    const BondTable& bonds = sim.state().bonds;
    const BondSlots s = make_bond_slots(bonds);
    const std::size_t n = bonds.particle_count();
    ASSERT_EQ(s.particles, n);
    ASSERT_FALSE(s.directions.empty());
    // The directions' spans lie end to end, each inside [0, n).
    std::size_t base = 0;
    for (const BondSlots::Direction& d : s.directions) {
      EXPECT_EQ(d.base, base);
      ASSERT_LT(d.first, d.last);
      ASSERT_LE(d.last + d.offset, n);
      base += d.last - d.first;
    }
    ASSERT_EQ(s.dense_slots, base);
    std::set<std::uint32_t> used;
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const std::uint32_t slot = s.entry_slot[b];
        ASSERT_LT(slot, s.slot_count());
        if (j < i) {
          EXPECT_EQ(slot, s.entry_slot[entry_of(bonds, j, i)]) << i << ", " << j;
          continue;
        }
        EXPECT_TRUE(used.insert(slot).second) << "slot " << slot << " used twice";
        // The slot says which bond it holds: owner and partner.
        if (slot < s.dense_slots) {
          // The direction whose span of slots holds it names the bond.
          const auto d = std::find_if(s.directions.begin(), s.directions.end(),
                                      [&](const BondSlots::Direction& u) {
                                        return slot >= u.base && slot < u.base + (u.last - u.first);
                                      });
          ASSERT_NE(d, s.directions.end()) << "a dense slot of no direction";
          EXPECT_EQ(d->offset, j - i);
          EXPECT_EQ(slot, d->slot(i));
        } else {
          EXPECT_EQ(s.extra_owner[slot - s.dense_slots], i);
          EXPECT_EQ(s.extra_partner[slot - s.dense_slots], j);
        }
      }
    EXPECT_EQ(used.size(), bonds.entry_count() / 2);
    EXPECT_TRUE(std::is_sorted(s.extra_owner.begin(), s.extra_owner.end()));
  }
}

TEST(BondSlots, RunsCoverEveryParticleAndPatternsReproduceTheirRows) {
  for (const CaseSpec& spec : cases()) {
    Simulation sim(spec);
    const BondTable& bonds = sim.state().bonds;
    const BondSlots s = make_bond_slots(bonds);
    std::size_t next = 0, on_patterns = 0;
    for (const BondSlots::Run& run : s.runs) {
      ASSERT_EQ(run.begin, next);
      ASSERT_LT(run.begin, run.end);
      next = run.end;
      if (run.pattern < 0) continue;
      const BondSlots::Pattern& pattern = s.patterns[static_cast<std::size_t>(run.pattern)];
      for (std::size_t m = run.begin; m < run.end; ++m) {
        ASSERT_EQ(bonds.end(m) - bonds.begin(m), pattern.slot_shift.size()) << m;
        for (std::size_t k = 0; k < pattern.slot_shift.size(); ++k) {
          const std::uint32_t b = bonds.begin(m) + static_cast<std::uint32_t>(k);
          const auto mm = static_cast<std::ptrdiff_t>(m);
          EXPECT_EQ(static_cast<std::ptrdiff_t>(bonds.neighbor[b]), mm + pattern.partner_shift[k]);
          EXPECT_EQ(static_cast<std::ptrdiff_t>(s.entry_slot[b]), mm + pattern.slot_shift[k]);
        }
      }
      on_patterns += run.end - run.begin;
    }
    EXPECT_EQ(next, bonds.particle_count());
    // The fast path is the common one: most of the rod is interior (the
    // 12 x 7 block is mostly surface).
    if (bonds.particle_count() > 1000) {
      EXPECT_GT(on_patterns, bonds.particle_count() / 2);
    }
    EXPECT_GT(on_patterns, 0u);
  }
}

TEST(BondSlots, SlotValuesAreTheOwnersEntriesAndZeroInEmptySlots) {
  Simulation sim(testing::rod_case());
  const BondTable& bonds = sim.state().bonds;
  const BondSlots s = make_bond_slots(bonds);
  const std::vector<double> r0x = slot_values(s, bonds, bonds.r0x);
  std::vector<bool> filled(s.slot_count(), false);
  for (std::size_t i = 0; i < bonds.particle_count(); ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
      if (bonds.neighbor[b] > i) {
        EXPECT_EQ(r0x[s.entry_slot[b]], bonds.r0x[b]);
        filled[s.entry_slot[b]] = true;
      }
  for (std::size_t k = 0; k < s.slot_count(); ++k)
    if (!filled[k]) {
      EXPECT_EQ(r0x[k], 0.0) << k;
    }
}

// gather_lanes finishes every particle of a block exactly once (as a new
// lane of a group, or by its row), and each group's eight particles lie in
// the block and share the group's pattern: whatever the blocks' cut.
TEST(BondSlots, LaneGroupsCoverEachParticleOnceInsideTheirRun) {
  for (const CaseSpec& spec : cases()) {
    Simulation sim(spec);
    const BondTable& bonds = sim.state().bonds;
    const BondSlots s = make_bond_slots(bonds);
    const std::size_t n = bonds.particle_count();
    std::vector<std::int32_t> pattern_of(n, -1);
    for (const BondSlots::Run& run : s.runs)
      for (std::size_t i = run.begin; i < run.end; ++i) pattern_of[i] = run.pattern;
    std::size_t groups = 0;
    for (const std::size_t cut : {std::size_t{1}, std::size_t{7}, std::size_t{64}, n}) {
      std::vector<int> finished(n, 0);
      for (std::size_t b = 0; b < n; b += cut) {
        const Range block{b, std::min(n, b + cut)};
        gather_lanes(
            s, block,
            [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t first) {
              ++groups;
              ASSERT_LT(first, kLanes);
              ASSERT_GE(m, block.begin);
              ASSERT_LE(m + kLanes, block.end);
              for (std::size_t k = 0; k < kLanes; ++k) {
                ASSERT_EQ(&s.patterns[static_cast<std::size_t>(pattern_of[m + k])], &pattern);
                if (k >= first) ++finished[m + k];
              }
            },
            [&](std::size_t i) {
              ASSERT_GE(i, block.begin);
              ASSERT_LT(i, block.end);
              ++finished[i];
            });
      }
      for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(finished[i], 1) << "particle " << i;
    }
    EXPECT_GT(groups, 0u);  // the lanes path ran
  }
}

}  // namespace
}  // namespace mpsolid
