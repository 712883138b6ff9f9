// Rigid bodies split between ranks (src/solver/split_rigid_bodies.hpp):
// a cut through a rigid body, in slabs or in pieces dealt round the ranks,
// steps to the serial run's bits (every owned particle, the body's pose
// and a driven body's work on each rank that holds some of it), threads as
// ranks; the cut splits a rigid body only when keeping it whole would
// unbalance the ranks, and bands do cut a long rigid rail.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "src/distributed/decomposition.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/part_cut.hpp"
#include "src/solver/part_setup.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/serial_bits.hpp"
#include "tests/support/test_cases.hpp"
#include "tests/support/thread_team.hpp"

namespace mpsolid {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

CaseSpec strip_on_a_rail(const std::vector<std::string>& overrides = {}) {
  return load_case(testing::source_path("tests/support/strip_on_a_rail.toml"), overrides);
}

// Slabs whose every cut falls inside the first rigid body, off its chunks.
Decomposition slabs_through(const SolverState& s, int ranks) {
  const Range body = s.rigid_bodies.front().range;
  std::vector<std::size_t> starts{0};
  for (int r = 1; r < ranks; ++r) starts.push_back(body.begin + body.size() * r / ranks + 37);
  starts.push_back(s.particles.size());
  Decomposition d;
  d.starts = starts;
  return d;
}

// Pieces of `width` dealt round the ranks: every body split, most chunks shared.
Decomposition dealt(std::size_t particles, int ranks, std::size_t width) {
  std::vector<std::size_t> starts;
  std::vector<int> owners;
  for (std::size_t b = 0; b < particles; b += width) {
    starts.push_back(b);
    owners.push_back(static_cast<int>(starts.size() % static_cast<std::size_t>(ranks)));
  }
  starts.push_back(particles);
  return decomposition_in_pieces(starts, owners, ranks);
}

// After `steps` decomposed steps on `d`, which splits a rigid body, every
// owned particle and every rigid body each rank holds (pose and work) are
// the serial run's.
void expect_serial_bits(const CaseSpec& spec, const Decomposition& d, std::int64_t steps) {
  const auto failures = testing::serial_bits_failures(spec, steps, [&](const SolverState& s) {
    bool split = false;
    for (const RigidBody& b : s.rigid_bodies) split |= d.owners_of(b.range).size() > 1;
    EXPECT_TRUE(split) << "the cut splits no rigid body";
    return d;
  });
  for (const std::string& f : failures) EXPECT_TRUE(f.empty()) << f;
}

void expect_serial_bits_through(const CaseSpec& spec, std::int64_t steps) {
  Simulation sim(spec);
  const SolverState& s = sim.state();
  for (const int ranks : {2, 3}) {
    SCOPED_TRACE(ranks);
    expect_serial_bits(spec, slabs_through(s, ranks), steps);
  }
  SCOPED_TRACE("pieces of 97 dealt round 3 ranks");
  expect_serial_bits(spec, dealt(s.particles.size(), 3, 97), steps);
}

TEST(SplitRigidBodies, AFreeRailTurningWithItsStripStepsToTheSerialBits) {
  expect_serial_bits_through(strip_on_a_rail(), 200);
  expect_serial_bits_through(strip_on_a_rail({"model=finite_strain"}), 200);
}

TEST(SplitRigidBodies, DrivenGripsStepToTheSerialBitsAndWork) {
  expect_serial_bits_through(
      load_case(testing::source_path("cases/holed_plate_grips.toml"), {"l0=0.001"}), 200);
}

TEST(SplitRigidBodies, ATumblingBrickInSpaceStepsToTheSerialBits) {
  expect_serial_bits_through(load_case(testing::source_path("cases/tumbling_brick.toml")), 300);
}

TEST(SplitRigidBodies, OneStepMoreIsCaught) {
  // The comparison above can fail: a part one step ahead of the serial run.
  const CaseSpec spec = strip_on_a_rail();
  Simulation serial(spec);
  const CaseSpec& run = serial.spec();
  const SolverState start = serial.state();
  const Decomposition d = slabs_through(start, 2);
  serial.advance(10);
  std::vector<int> differs(2, 0);
  testing::as_ranks(2, [&](const RankGroup& world, int me) {
    RankPart part = make_rank_part(run, local_part(start, d, me));
    advance_rank_part(part, world, run.dt, 11);
    for (const RigidBody& body : part.local.rigid_bodies)
      differs[static_cast<std::size_t>(me)] +=
          !same_bits(body.xg, serial.state().rigid_bodies.front().xg);
  });
  EXPECT_EQ(differs, (std::vector<int>{1, 1}));
}

TEST(SplitRigidBodies, TheCutSplitsOnlyARigidBodyTooLargeToKeepWhole) {
  // The rail is a quarter of the particles: kept whole only where a tenth
  // of a rank's share holds it; a body under a force always whole.
  const auto kept = [](const CaseSpec& spec, const std::string& name, int ranks) {
    std::size_t b = 0;
    while (spec.bodies.at(b).name != name) ++b;
    return static_cast<bool>(bodies_kept_whole(spec, body_layout(spec), ranks)[b]);
  };
  const CaseSpec rail = strip_on_a_rail();
  EXPECT_FALSE(kept(rail, "rail", 2));
  const CaseSpec small =
      strip_on_a_rail({"bodies.rail.x=[0.0, 0.01]", "bodies.rail.y=[-0.001, 0.0]"});
  EXPECT_TRUE(kept(small, "rail", 2));
  EXPECT_FALSE(kept(small, "rail", 40));
  EXPECT_TRUE(kept(testing::rod_case({"l0=0.002"}), "plate", 8));
  // Bands along the rail split it over every rank, and step to the serial bits.
  for (const int ranks : {2, 3, 4}) {
    SCOPED_TRACE(ranks);
    const CaseCut cut = cut_case(rail, ranks, CutChoice::bands);
    EXPECT_EQ(cut.kind, "bands along x");
    Simulation sim(rail);
    EXPECT_EQ(cut.decomposition.owners_of(sim.state().rigid_bodies.front().range).size(),
              static_cast<std::size_t>(ranks));
    if (ranks == 3) expect_serial_bits(rail, cut.decomposition, 200);
  }
}

}  // namespace
}  // namespace mpsolid
