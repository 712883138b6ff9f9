// The cut of a case over ranks (src/solver/part_cut.hpp): a long body stored
// along its length is cut across it in bands, whose halo is smaller than the
// slabs' (the estimate and the real halo agree on that), every particle is
// owned once, bodies kept whole stay whole, and the decomposed step on a cut
// in pieces gives the serial run's bits (threads as ranks).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "src/distributed/decomposition.hpp"
#include "src/distributed/part_message.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/part_cut.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/simulation.hpp"
#include "src/solver/time_step_choice.hpp"
#include "tests/support/serial_bits.hpp"
#include "tests/support/test_cases.hpp"
#include "tests/support/thread_team.hpp"

namespace mpsolid {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

CaseSpec case_of(const std::string& file, const std::vector<std::string>& overrides = {}) {
  return load_case(testing::source_path(file), overrides);
}

std::size_t ghosts_of(const BondTable& bonds, const Decomposition& d) {
  std::size_t n = 0;
  for (int r = 0; r < d.ranks(); ++r) n += plan_halo(bonds, d, r).ghosts.size();
  return n;
}

TEST(PartCut, ALongStripIsCutAcrossItsLength) {
  Simulation sim(case_of("cases/wave_strip.toml"));
  const SolverState& s = sim.state();
  for (const int ranks : {2, 3, 4}) {
    SCOPED_TRACE(ranks);
    const CaseCut cut = cut_case(sim.spec(), ranks);
    EXPECT_EQ(cut.kind, "bands along x");
    EXPECT_LT(cut.band_ghosts, 0.2 * cut.slab_ghosts);
    const Decomposition& d = cut.decomposition;
    ASSERT_FALSE(d.slabs());
    EXPECT_EQ(d.ranks(), ranks);
    EXPECT_EQ(d.particles(), s.particles.size());
    // Every particle owned once, by a rank in range; pieces ascending.
    std::vector<int> owner(s.particles.size(), -1);
    for (int r = 0; r < ranks; ++r)
      for (const Range piece : d.pieces(r))
        for (std::size_t i = piece.begin; i < piece.end; ++i) {
          EXPECT_EQ(owner[i], -1) << i;
          owner[i] = r;
          EXPECT_EQ(d.owner_of(i), r) << i;
        }
    EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0);
    // The rigid driver whole on one rank.
    for (const RigidBody& b : s.rigid_bodies)
      for (std::size_t i = b.range.begin; i < b.range.end; ++i)
        EXPECT_EQ(owner[i], owner[b.range.begin]);
    // Balanced to within a column of the strip (10 particles) or the driver.
    for (int r = 0; r < ranks; ++r) {
      std::size_t n = 0;
      for (const Range piece : d.pieces(r)) n += piece.size();
      EXPECT_NEAR(static_cast<double>(n), static_cast<double>(s.particles.size()) / ranks, 30.0);
    }
    // The real halo agrees with the estimate: the bands' is far smaller.
    EXPECT_LT(ghosts_of(s.bonds, d),
              ghosts_of(s.bonds, cut_case(sim.spec(), ranks, CutChoice::slabs).decomposition) / 4);
  }
}

TEST(PartCut, ABlockStoredAcrossItsLengthKeepsItsSlabs) {
  // 10 wide, 80 high: rows along x are short, so slabs already cut across.
  CaseSpec spec = testing::free_block_case(10, 80, false);
  const CaseCut cut = cut_case(spec, 3);
  EXPECT_EQ(cut.kind, "slabs");
  EXPECT_TRUE(cut.decomposition.slabs());
  EXPECT_LE(cut.slab_ghosts, cut.band_ghosts);
}

TEST(PartCut, AForcedCutStillReportsBothEstimates) {
  const CaseCut auto_cut = cut_case(case_of("cases/wave_strip.toml"), 3);
  const CaseCut slabs = cut_case(case_of("cases/wave_strip.toml"), 3, CutChoice::slabs);
  EXPECT_EQ(slabs.kind, "slabs");
  EXPECT_TRUE(slabs.decomposition.slabs());
  EXPECT_EQ(slabs.slab_ghosts, auto_cut.slab_ghosts);
  EXPECT_EQ(slabs.band_ghosts, auto_cut.band_ghosts);
  EXPECT_GT(slabs.slab_ghosts, 0.0);
}

// A square plate at four ranks: quarters (recursive bisection) hold a
// smaller halo than bands or slabs, and the estimate says so; at two ranks
// one halving is the bands' cut.
TEST(PartCut, ASquarePlateAtFourRanksIsCutInBlocks) {
  const CaseSpec spec = case_of("cases/spinning_plate.toml");
  Simulation sim(spec);
  const SolverState& s = sim.state();
  const CaseCut cut = cut_case(spec, 4);
  EXPECT_EQ(cut.kind, "blocks");
  EXPECT_LT(cut.block_ghosts, 0.8 * std::min(cut.slab_ghosts, cut.band_ghosts));
  const Decomposition& d = cut.decomposition;
  std::vector<int> owner(s.particles.size(), -1);
  for (int r = 0; r < 4; ++r) {
    std::size_t n = 0;
    for (const Range piece : d.pieces(r))
      for (std::size_t i = piece.begin; i < piece.end; ++i) {
        EXPECT_EQ(owner[i], -1) << i;
        owner[i] = r;
        ++n;
      }
    // Balanced to within two of the plate's columns.
    EXPECT_NEAR(static_cast<double>(n), static_cast<double>(s.particles.size()) / 4,
                2.0 * std::sqrt(static_cast<double>(s.particles.size())));
  }
  EXPECT_EQ(std::count(owner.begin(), owner.end(), -1), 0);
  // The real halo agrees with the estimate.
  EXPECT_LT(ghosts_of(s.bonds, d),
            ghosts_of(s.bonds, cut_case(spec, 4, CutChoice::bands).decomposition));
  const CaseCut halves = cut_case(spec, 2);
  EXPECT_EQ(halves.block_ghosts, halves.band_ghosts);
  EXPECT_NE(halves.kind, "blocks");
}

// The decomposed step on `cut(start state)`, threads as ranks: after
// `steps` steps every owned particle has the serial run's state, bit for
// bit.
void expect_serial_bits_on(const CaseSpec& spec, int ranks, std::int64_t steps,
                           const std::function<Decomposition(const SolverState&)>& cut_of) {
  const auto failures = testing::serial_bits_failures(spec, steps, [&](const SolverState& s) {
    const Decomposition cut = cut_of(s);
    EXPECT_FALSE(cut.slabs());
    EXPECT_EQ(cut.ranks(), ranks);
    return cut;
  });
  for (const std::string& f : failures) EXPECT_TRUE(f.empty()) << f;
}
void expect_serial_bits_on_bands(const CaseSpec& spec, int ranks, std::int64_t steps) {
  expect_serial_bits_on(spec, ranks, steps, [&](const SolverState&) {
    return cut_case(spec, ranks, CutChoice::bands).decomposition;
  });
}

TEST(PartCut, StepsOnBlocksGiveTheSerialBits) {
  for (const auto& [file, ranks] :
       std::vector<std::pair<std::string, int>>{{"cases/spinning_plate.toml", 4},
                                                {"cases/spinning_plate.toml", 3},
                                                {"cases/spinning_cube.toml", 4}}) {
    SCOPED_TRACE(file + " at " + std::to_string(ranks) + " ranks");
    const CaseSpec spec = case_of(file);
    EXPECT_EQ(cut_case(spec, ranks, CutChoice::blocks).kind, "blocks");
    expect_serial_bits_on(spec, ranks, 200, [&](const SolverState&) {
      return cut_case(spec, ranks, CutChoice::blocks).decomposition;
    });
  }
}

// Contact on a cut in pieces: the ranks' own candidates are interleaved in
// candidate order, and a band's bond rows need not ascend (a bonded pair
// taken for a contact pair fails it at the first step). The colliding
// blocks meet after about 450 steps.
TEST(PartCut, ContactOnBandsStepsToTheSerialBits) {
  const CaseSpec blocks = case_of("cases/colliding_blocks.toml");
  {
    // By step 700 contact has moved them: without it they would be elsewhere.
    Simulation touching(blocks);
    Simulation passing(case_of("cases/colliding_blocks.toml", {"contact.enabled=false"}));
    touching.advance(700);
    passing.advance(700);
    EXPECT_NE(touching.particles().vx, passing.particles().vx)
        << "the blocks do not touch by step 700";
  }
  expect_serial_bits_on_bands(blocks, 3, 700);
  // Pieces of 37 dealt round the ranks: every rank's candidates in runs
  // all over the candidate order.
  expect_serial_bits_on(blocks, 3, 700, [](const SolverState& s) {
    std::vector<std::size_t> starts;
    std::vector<int> owners;
    for (std::size_t b = 0; b < s.particles.size(); b += 37) {
      starts.push_back(b);
      owners.push_back(static_cast<int>(starts.size() % 3));
    }
    starts.push_back(s.particles.size());
    return decomposition_in_pieces(starts, owners, 3);
  });
  // In space, and a rigid disk striking a block (contact with a rigid body).
  expect_serial_bits_on_bands(case_of("cases/colliding_spheres.toml", {"l0=0.002"}), 2, 300);
  expect_serial_bits_on_bands(case_of("cases/disk_impact.toml"), 3, 400);
}

TEST(PartCut, StepsOnBandsGiveTheSerialBits) {
  expect_serial_bits_on_bands(case_of("cases/wave_strip.toml"), 3, 300);
  expect_serial_bits_on_bands(testing::rod_case({"l0=0.002"}), 2, 200);
  expect_serial_bits_on_bands(testing::rod_case({"l0=0.002", "model=finite_strain"}), 3, 200);
  expect_serial_bits_on_bands(testing::rod_case({"l0=0.002", "model=paper_conservative"}), 4, 200);
  // In space the kernels gather by row patterns, which a part in pieces
  // must not take for the rows that reach its ghosts after its own.
  expect_serial_bits_on_bands(case_of("cases/shock_rod_3d.toml", {"l0=0.003"}), 3, 100);
  expect_serial_bits_on_bands(case_of("cases/shock_rod_3d.toml", {"l0=0.003", "model=paper"}), 4,
                              100);
}

// The stable step estimated on bands (every rank its part, threads as
// ranks) is the one-process estimate, bit for bit.
void expect_the_serial_stable_step_on_bands(const CaseSpec& spec, int ranks,
                                            CutChoice choice = CutChoice::bands) {
  PhaseTimers timers;
  SolverState global = set_up(spec, timers);
  finish_set_up(global, spec);
  const StableStepEstimate serial = estimate_case_stable_step(spec, global);
  const CaseCut cut = cut_case(spec, ranks, choice);
  std::vector<StableStepEstimate> got(static_cast<std::size_t>(ranks));
  testing::as_ranks(ranks, [&](const RankGroup& world, int me) {
    RankPart part = make_rank_part(spec, local_part(global, cut.decomposition, me));
    got[static_cast<std::size_t>(me)] = estimate_part_stable_step(spec, part, world);
  });
  for (const StableStepEstimate& e : got) {
    EXPECT_TRUE(same_bits(e.omega_max, serial.omega_max))
        << spec.name << " at " << ranks << " ranks: " << e.omega_max << ", serially "
        << serial.omega_max;
    EXPECT_EQ(e.iterations, serial.iterations);
  }
}

TEST(PartCut, TheStableStepOnBandsIsTheSerialOne) {
  for (const int ranks : {2, 3, 4}) {
    expect_the_serial_stable_step_on_bands(testing::rod_case({"l0=0.004", "time.dt=\"auto\""}),
                                           ranks);
    expect_the_serial_stable_step_on_bands(case_of("cases/shock_rod_3d.toml", {"l0=0.003"}), ranks,
                                           CutChoice::slabs);
    expect_the_serial_stable_step_on_bands(case_of("cases/shock_rod_3d.toml", {"l0=0.003"}), ranks);
  }
}

}  // namespace
}  // namespace mpsolid
