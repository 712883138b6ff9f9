// A rank's part set up from the case alone (src/solver/part_setup.hpp) is the
// part rank 0 cuts from the whole set-up state (local_part), bit for bit, as
// the message it would travel in: every case in cases/ the set-up covers, in
// the plane and in space, at 2, 3 and 5 ranks.
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "src/core/parallel.hpp"
#include "src/distributed/bond_table_facts.hpp"
#include "src/distributed/part_message.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/part_setup.hpp"
#include "src/solver/setup.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

std::vector<double> message_of(const LocalPart& part) {
  std::vector<double> all;
  pack_local_part(part, [&](const std::vector<double>& piece) {
    all.insert(all.end(), piece.begin(), piece.end());
  });
  return all;
}

// A case and its whole set-up state as a run makes them before its step is
// fixed (set-up reads no dt; the loads are scheduled after).
struct Whole {
  CaseSpec spec;
  SolverState state;
};
Whole whole_state(const std::string& case_file, const std::vector<std::string>& overrides) {
  PhaseTimers timers;
  Whole w{load_case(testing::source_path(case_file), overrides), {}};
  w.state = set_up(w.spec, timers);
  finish_set_up(w.state, w.spec);
  return w;
}

// Each rank's part both ways, at several rank counts.
void expect_the_whole_states_parts(const std::string& case_file,
                                   const std::vector<std::string>& overrides = {}) {
  const Whole w = whole_state(case_file, overrides);
  const CaseSpec& spec = w.spec;
  const SolverState& global = w.state;
  ASSERT_TRUE(part_set_up_covers(spec)) << case_file;
  for (const int ranks : {2, 3, 5}) {
    const Decomposition d = decompose_state(global, ranks);
    for (int r = 0; r < ranks; ++r) {
      const std::vector<double> whole = message_of(local_part(global, d, r));
      const std::vector<double> alone = message_of(set_up_part(spec, d, r));
      ASSERT_EQ(whole.size(), alone.size()) << case_file << ", rank " << r << " of " << ranks;
      std::size_t first = 0;
      while (first < whole.size() && std::memcmp(&whole[first], &alone[first], sizeof(double)) == 0)
        ++first;
      EXPECT_EQ(first, whole.size())
          << case_file << ", rank " << r << " of " << ranks << ": differs at value " << first
          << " (" << whole[first] << " from the whole state, " << alone[first] << " alone)";
    }
  }
}

TEST(PartSetUp, TheRodWithItsWallPlateAndForce) {
  expect_the_whole_states_parts("cases/shock_rod.toml");
}
TEST(PartSetUp, TheRodWithProbesAndAFiniteStrainModel) {
  expect_the_whole_states_parts("cases/shock_rod_55kN_short_wall.toml");
}
// The plate (rigid, another rank's) moving and turning from the start: the
// rod's rank holds its bonded particles as ghosts, placed as it moves.
TEST(PartSetUp, AMovingRigidBodyAnotherRankOwns) {
  expect_the_whole_states_parts("cases/shock_rod.toml",
                                {"bodies.plate.velocity=[3.0, -1.0]", "bodies.plate.spin=40.0"});
}
TEST(PartSetUp, ASpinningPlate) {
  expect_the_whole_states_parts("cases/spinning_plate.toml");
}
TEST(PartSetUp, ABendingModeWithTheAutomaticStep) {
  expect_the_whole_states_parts("cases/oscillating_plate.toml");
}
TEST(PartSetUp, AHeldStrip) {
  expect_the_whole_states_parts("cases/wave_strip.toml");
}
TEST(PartSetUp, AHoledPlateWithDrivenGrips) {
  expect_the_whole_states_parts("cases/holed_plate_grips.toml");
}
TEST(PartSetUp, TheRodInSpaceGluedToItsWall) {
  expect_the_whole_states_parts("cases/shock_rod_3d.toml");
}
TEST(PartSetUp, ACantileverInSpace) {
  expect_the_whole_states_parts("cases/cantilever_beam.toml");
}
TEST(PartSetUp, ASpinningCube) {
  expect_the_whole_states_parts("cases/spinning_cube.toml");
}
TEST(PartSetUp, ATumblingBrick) {
  expect_the_whole_states_parts("cases/tumbling_brick.toml");
}

// What rank 0 keeps when it holds no particle, from every rank's part set
// up alone on the cut made from the case (decompose_case): the bond table's
// count and hash (the ranks hashing in turn, threads as ranks), and every
// rigid body and load, are the whole state's.
LocalLayout whole_layout(const SolverState& s) {
  LocalLayout layout;
  layout.owned = layout.owned_global = s.particles.all();
  return layout;
}
void expect_the_whole_states_head(const std::string& case_file,
                                  const std::vector<std::string>& overrides = {}) {
  const Whole w = whole_state(case_file, overrides);
  std::vector<double> whole_items;
  append_owned_items(w.state, whole_layout(w.state), whole_items);
  for (const int ranks : {2, 3, 5}) {
    SCOPED_TRACE(case_file + ", " + std::to_string(ranks) + " ranks");
    const Decomposition d = decompose_case(w.spec, ranks);
    std::vector<LocalPart> parts;
    for (int r = 0; r < ranks; ++r) parts.push_back(set_up_part(w.spec, d, r));
    std::vector<BondTableFacts> facts(static_cast<std::size_t>(ranks));
    set_thread_count(ranks);
    ThreadMailboxes boxes(ranks);
    run_in_team([&] {
      const auto me = static_cast<int>(team_rank());
      serial_section([&] {
        const LocalPart& part = parts[static_cast<std::size_t>(me)];
        facts[static_cast<std::size_t>(me)] =
            bond_table_facts(part.state.bonds, part.layout, ThreadRanks(boxes, me));
      });
    });
    set_thread_count(1);
    for (const BondTableFacts& f : facts) {
      EXPECT_EQ(f.count, w.state.bonds.entry_count() / 2);
      EXPECT_EQ(f.hash, w.state.bonds.hash());
    }
    SolverState head;
    for (const LocalPart& part : parts) {
      std::vector<double> mine;
      append_owned_items(part.state, part.layout, mine);
      std::size_t at = 0;
      read_owned_items(mine, at, head);
      EXPECT_EQ(at, mine.size());
    }
    put_loads_in_case_order(w.spec, head.loads);
    std::vector<double> head_items;
    append_owned_items(head, whole_layout(head), head_items);
    EXPECT_TRUE(head_items == whole_items);
  }
}

TEST(PartSetUp, TheRanksGiveTheWholeBondTablesFactsAndEveryBodyAndLoad) {
  expect_the_whole_states_head("cases/shock_rod.toml",
                               {"bodies.plate.velocity=[3.0, -1.0]", "bodies.plate.spin=40.0"});
  expect_the_whole_states_head("cases/holed_plate_grips.toml");
  expect_the_whole_states_head("cases/shock_rod_3d.toml");
  expect_the_whole_states_head("cases/tumbling_brick.toml");
  set_thread_count(available_cores());
}

// A cut through the plate (a rigid body) is refused both ways.
TEST(PartSetUp, ARigidBodyCutInTwoIsRefused) {
  const Whole w = whole_state("cases/shock_rod.toml", {});
  std::size_t b = 0;
  while (w.spec.bodies[b].name != "plate") ++b;
  const Range plate = w.state.body_ranges[b];
  ASSERT_EQ(w.spec.bodies[b].kind, Kind::rigid);
  Decomposition d;
  d.starts = {0, plate.begin + plate.size() / 2, w.state.particles.size()};
  for (const int r : {0, 1}) {
    EXPECT_THROW(local_part(w.state, d, r), std::invalid_argument);
    EXPECT_THROW(set_up_part(w.spec, d, r), std::invalid_argument);
  }
}

TEST(PartSetUp, CasesWithContactAGasOrAPressureAreLeftToTheWholeState) {
  for (const char* file :
       {"cases/colliding_blocks.toml", "cases/giordano_panel.toml", "cases/ring_pressure.toml"})
    EXPECT_FALSE(part_set_up_covers(load_case(testing::source_path(file)))) << file;
}

}  // namespace
}  // namespace mpsolid
