// A rank's part set up from the case alone (src/solver/part_setup.hpp) is the
// part rank 0 cuts from the whole set-up state (local_part), bit for bit, as
// the message it would travel in: every case in cases/ the set-up covers, in
// the plane and in space, at 2, 3 and 5 ranks. And what rank 0 keeps when it
// holds no particle, from the ranks' parts: the bond table's facts, every
// body and load, its copy of the contact candidates, a pressure's work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/bond_table_facts.hpp"
#include "src/distributed/part_message.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/contact_copy.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/gas_outlines.hpp"
#include "src/solver/part_setup.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"
#include "tests/support/thread_team.hpp"

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

using testing::as_ranks;

// Every rank's part set up alone, the ranks together (with contact they
// share their candidates).
std::vector<LocalPart> parts_set_up_alone(const CaseSpec& spec, const Decomposition& d) {
  std::vector<LocalPart> parts(static_cast<std::size_t>(d.ranks()));
  as_ranks(d.ranks(), [&](const RankGroup& world, int me) {
    parts[static_cast<std::size_t>(me)] = set_up_part(spec, d, me, &world);
  });
  return parts;
}

// Each rank's part of the cut `d` both ways.
void expect_the_same_parts(const std::string& case_file, const Whole& w, const Decomposition& d) {
  const CaseSpec& spec = w.spec;
  const SolverState& global = w.state;
  const int ranks = d.ranks();
  {
    const std::vector<LocalPart> parts = parts_set_up_alone(spec, d);
    for (int r = 0; r < ranks; ++r) {
      const std::vector<double> whole = message_of(local_part(global, d, r));
      const std::vector<double> alone = message_of(parts[static_cast<std::size_t>(r)]);
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

// Each rank's part both ways, at several rank counts.
void expect_the_whole_states_parts(const std::string& case_file,
                                   const std::vector<std::string>& overrides = {}) {
  const Whole w = whole_state(case_file, overrides);
  for (const int ranks : {2, 3, 5})
    expect_the_same_parts(case_file, w, decompose_state(w.state, ranks));
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
// Contact: every candidate of the run in every part, found by the rank
// that owns it.
TEST(PartSetUp, CollidingBlocks) {
  expect_the_whole_states_parts("cases/colliding_blocks.toml");
}
TEST(PartSetUp, ADiskHittingABlock) {
  expect_the_whole_states_parts("cases/disk_impact.toml");
}
TEST(PartSetUp, TheRodPressingOnItsWallAndPlate) {
  expect_the_whole_states_parts("cases/shock_rod_55kN.toml");
}
TEST(PartSetUp, CollidingSpheres) {
  expect_the_whole_states_parts("cases/colliding_spheres.toml");
}
TEST(PartSetUp, TheRodInSpaceWithContact) {
  expect_the_whole_states_parts("cases/shock_rod_3d.toml", {"contact.enabled=true"});
}
// Pressure loads: every part holds every node, positioning those whose
// host it owns.
TEST(PartSetUp, APressurisedRing) {
  expect_the_whole_states_parts("cases/ring_pressure.toml");
}
TEST(PartSetUp, TheRodUnderAPressure) {
  expect_the_whole_states_parts("cases/shock_rod_pressure.toml");
}
TEST(PartSetUp, ADiskUnderABlastWave) {
  expect_the_whole_states_parts("cases/disk_blast.toml");
}
TEST(PartSetUp, TheRodInSpaceUnderAPressureWithContact) {
  expect_the_whole_states_parts("cases/shock_rod_3d_pressure.toml");
}
// Each part holds the gas loads whole over the sites it holds, as pressures.
TEST(PartSetUp, APanelInAShockTube) {
  expect_the_whole_states_parts("cases/giordano_panel.toml");
}
TEST(PartSetUp, TheRodStruckThroughAGas) {
  expect_the_whole_states_parts("cases/shock_rod_gas.toml");
}

// What rank 0 keeps when it holds no particle, from every rank's part set
// up alone on the cut made from the case (decompose_case): the bond table's
// count and hash (the ranks hashing in turn, threads as ranks), and every
// rigid body and load, are the whole state's.
std::vector<std::string> body_names(const CaseSpec& spec) {
  std::vector<std::string> names;
  for (const BodySpec& b : spec.bodies) names.push_back(b.name);
  return names;
}
LocalLayout whole_layout(const SolverState& s) {
  LocalLayout layout;
  layout.owned = s.particles.all();
  layout.set_owned_pieces({s.particles.all()});
  return layout;
}
void expect_the_whole_states_head(const std::string& case_file,
                                  const std::vector<std::string>& overrides = {}) {
  const Whole w = whole_state(case_file, overrides);
  std::vector<double> whole_items;
  {
    // Rank 0 keeps each rigid body's pose and make-up, not its particles'
    // offsets.
    SolverState whole = w.state;
    merge_rigid_bodies(whole, body_names(w.spec));
    append_owned_items(whole, whole_layout(whole), whole_items);
  }
  for (const int ranks : {2, 3, 5}) {
    SCOPED_TRACE(case_file + ", " + std::to_string(ranks) + " ranks");
    const Decomposition d = decompose_case(w.spec, ranks);
    const std::vector<LocalPart> parts = parts_set_up_alone(w.spec, d);
    std::vector<BondTableFacts> facts(static_cast<std::size_t>(ranks));
    as_ranks(ranks, [&](const RankGroup& world, int me) {
      const LocalPart& part = parts[static_cast<std::size_t>(me)];
      facts[static_cast<std::size_t>(me)] = bond_table_facts(part.state.bonds, part.layout, world);
    });
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
    head.body_ranges = w.state.body_ranges;
    merge_rigid_bodies(head, body_names(w.spec));
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
}

// A rigid body split between ranks: each rank's part of it (its own
// particles' offsets, the whole body's pose and make-up, its ghosts placed)
// the same both ways, cut in slabs through it or in pieces dealt round.
TEST(PartSetUp, RigidBodiesSplitBetweenRanks) {
  for (const std::string file : {"cases/holed_plate_grips.toml", "cases/tumbling_brick.toml"}) {
    const Whole w = whole_state(file, {});
    const Range body = w.state.rigid_bodies.front().range;
    const std::size_t n = w.state.particles.size();
    Decomposition slabs;
    slabs.starts = {0, body.begin + body.size() / 3 + 5, body.begin + 2 * body.size() / 3 + 7, n};
    expect_the_same_parts(file, w, slabs);
    std::vector<std::size_t> starts;
    std::vector<int> owners;
    for (std::size_t b = 0; b < n; b += 61) {
      starts.push_back(b);
      owners.push_back(static_cast<int>(starts.size() % 3));
    }
    starts.push_back(n);
    expect_the_same_parts(file, w, decomposition_in_pieces(starts, owners, 3));
  }
}

// A cut through the plate (a rigid body under a force, whose share and
// centroid sum over all of it) is refused both ways.
TEST(PartSetUp, ABodyUnderAForceCutInTwoIsRefused) {
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

// Contact needs the ranks: a part set up without them is a mistake.
TEST(PartSetUp, ContactWithoutTheRanksIsRefused) {
  const CaseSpec spec = load_case(testing::source_path("cases/colliding_blocks.toml"));
  EXPECT_THROW(set_up_part(spec, decompose_case(spec, 2), 0), std::logic_error);
}

// Rank 0's copy of the candidates (src/solver/contact_copy.hpp), from its
// part set up alone, is the whole state's contact: the same candidates,
// groups and walls, the same bonds between them, and the same contact
// energy, closest pair and interpenetration verdict, at rest and with the
// moving candidates moved about.
void expect_the_whole_states_candidates(const std::string& case_file) {
  Whole w = whole_state(case_file, {});
  ContactState& whole = w.state.contact;
  ParticleStore& p = w.state.particles;
  for (const int ranks : {2, 3}) {
    SCOPED_TRACE(case_file + ", " + std::to_string(ranks) + " ranks");
    const std::vector<LocalPart> parts = parts_set_up_alone(w.spec, decompose_case(w.spec, ranks));
    ContactState c;
    ContactCopy copy = copy_contact_candidates(parts[0].state, parts[0].layout, c);
    ASSERT_EQ(copy.storage_index, whole.candidates);
    EXPECT_EQ(c.group, whole.group);
    EXPECT_EQ(c.first_moving, whole.first_moving);
    for (std::size_t a = 0; a < c.size(); ++a)
      for (std::size_t b = 0; b < c.size(); ++b) {
        const std::size_t i = whole.candidates[a], j = whole.candidates[b];
        const auto row = w.state.bonds.neighbor.begin();
        const bool bonded = std::binary_search(row + w.state.bonds.begin(i),
                                               row + w.state.bonds.end(i), std::uint32_t(j));
        const auto copy_row = copy.bonds.neighbor.begin();
        ASSERT_EQ(bonded, std::binary_search(copy_row + copy.bonds.begin(a),
                                             copy_row + copy.bonds.end(a), std::uint32_t(b)))
            << a << ", " << b;
      }
    // Each moving candidate moved on both by up to a contact distance along
    // each axis, so that unbonded surface pairs (sqrt 5 l0 apart) touch.
    std::uint64_t seed = 12345;
    std::vector<double> moved;
    for (std::size_t a = whole.first_moving; a < whole.size(); ++a) {
      for (std::vector<double>* axis : {&p.x, &p.y, &p.z}) {
        if (axis == &p.z && p.dimension != 3) continue;
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        const double shift = (static_cast<double>(seed >> 11) / 9007199254740992.0 - 0.5) * 2.0 *
                             whole.parameters.distance;
        (*axis)[whole.candidates[a]] += shift;
        moved.push_back((*axis)[whole.candidates[a]]);
      }
    }
    place_moving_candidates(copy, c, moved);
    refresh_contact_list(whole, p, w.state.bonds);
    refresh_contact_list(c, copy.particles, copy.bonds);
    const double reach = contact_search_reach(w.spec);
    const ClosestContact a = closest_contact(whole, p, w.state.bonds, reach);
    const ClosestContact b = closest_contact(c, copy.particles, copy.bonds, reach);
    ASSERT_TRUE(a.found);
    EXPECT_EQ(a.distance, b.distance);
    EXPECT_EQ(a.i, copy.storage_index.at(b.i));
    EXPECT_EQ(a.j, copy.storage_index.at(b.j));
    double whole_energy = 0, copy_energy = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      whole_energy += contact_energy_share(whole, p, k);
      copy_energy += contact_energy_share(c, copy.particles, k);
    }
    EXPECT_GT(whole_energy, 0.0);
    EXPECT_EQ(whole_energy, copy_energy);
    const StabilityVerdict v = check_interpenetration(whole, p);
    const StabilityVerdict u = check_interpenetration(c, copy.particles);
    EXPECT_EQ(v.ok, u.ok);
    EXPECT_EQ(v.value, u.value);
    EXPECT_EQ(v.particle, copy.storage_index.at(u.particle));
    // Undo the move for the next rank count.
    w = whole_state(case_file, {});
  }
}

TEST(PartSetUp, RankZerosCopyOfTheCandidatesIsTheWholeStatesContact) {
  expect_the_whole_states_candidates("cases/colliding_blocks.toml");
  expect_the_whole_states_candidates("cases/disk_impact.toml");
  expect_the_whole_states_candidates("cases/colliding_spheres.toml");
}

}  // namespace
}  // namespace mpsolid

namespace mpsolid {
namespace {

// A pressure's work over ranks (src/solver/rank_checks.cpp): the nodes each
// rank's part hosts, positioned from its own particles and ghosts, give
// every node once, and the work at those positions is the whole state's,
// bit for bit, mid-run (the ring inflating, the rod's plate pushed).
void expect_the_pressures_work_from_the_parts(const std::string& case_file, std::int64_t steps) {
  Simulation sim(load_case(testing::source_path(case_file)));
  sim.advance(steps);
  const SolverState& global = sim.state();
  ASSERT_TRUE(any_pressure(global.loads));
  for (const int ranks : {2, 3, 5}) {
    SCOPED_TRACE(case_file + ", " + std::to_string(ranks) + " ranks");
    const Decomposition d = decompose_state(global, ranks);
    std::vector<double> nodes;
    for (int r = 0; r < ranks; ++r) {
      const LocalPart part = local_part(global, d, r);
      append_hosted_node_positions(part.state.particles, part.state.loads, nodes);
    }
    std::size_t pressures = 0;
    for (const StepLoad& load : global.loads) {
      if (!load.is_pressure()) continue;
      ASSERT_TRUE(load.active);
      std::vector<double> xyz(3 * load.surface.nodes(), std::nan(""));
      std::size_t given = 0;
      for (std::size_t k = 0; k + 5 <= nodes.size(); k += 5) {
        if (static_cast<std::size_t>(nodes[k]) != pressures) continue;
        std::copy_n(nodes.begin() + static_cast<long>(k + 2), 3,
                    xyz.begin() + 3 * static_cast<long>(nodes[k + 1]));
        ++given;
      }
      EXPECT_EQ(given, load.surface.nodes()) << "every node once";
      const double whole = load_work(global.particles, load);
      EXPECT_NE(whole, 0.0);
      EXPECT_EQ(pressure_work_at(load, xyz), whole);
      ++pressures;
    }
  }
}

TEST(PressureOverRanks, TheWorkFromTheNodesThePartsHostIsTheWholeStates) {
  expect_the_pressures_work_from_the_parts("cases/ring_pressure.toml", 300);
  expect_the_pressures_work_from_the_parts("cases/shock_rod_pressure.toml", 300);
  expect_the_pressures_work_from_the_parts("cases/shock_rod_3d_pressure.toml", 100);
}

// A gas window over ranks (src/solver/gas_outlines.hpp): the outlines'
// nodes each part hosts give every node once, with the whole state's
// positions and velocities bit for bit, and the gas's forces given at them
// leave every part's gas loads as the whole state's (their work so far,
// running step and node forces), mid-run.
void expect_the_gas_window_from_the_parts(const std::string& case_file, std::int64_t steps) {
  Simulation sim(load_case(testing::source_path(case_file)));
  sim.advance(steps);
  const CaseSpec& spec = sim.spec();
  const SolverState& global = sim.state();
  const std::vector<PressureSurface> outlines = gas_outlines(spec, global.body_ranges);
  const OutlineMotion whole = outline_motion(global.particles, outlines);
  GasNodeForces forces;  // any forces: a ramp over the nodes
  for (const StepLoad& load : gas_loads(spec, global.body_ranges))
    for (std::size_t k = 0; k < 2 * load.surface.nodes(); ++k)
      forces.push_back(1e-3 * static_cast<double>(k) - 0.7);
  ASSERT_FALSE(forces.empty());
  std::vector<StepLoad> whole_loads = global.loads;
  give_gas_forces(spec, whole_loads, whole, forces);
  for (const int ranks : {2, 3, 5}) {
    SCOPED_TRACE(case_file + ", " + std::to_string(ranks) + " ranks");
    const Decomposition d = decompose_case(spec, ranks);
    std::vector<LocalPart> parts;
    std::vector<double> hosted;
    for (int r = 0; r < ranks; ++r) {
      parts.push_back(local_part(global, d, r));
      append_hosted_outline_motion(parts.back().state.particles,
                                   part_gas_outlines(spec, parts.back().state.loads,
                                                     parts.back().body_ranges, parts.back().layout),
                                   hosted);
    }
    const OutlineMotion shared = assemble_outline_motion(outlines, hosted);
    ASSERT_EQ(shared.size(), whole.size());
    for (std::size_t o = 0; o < whole.size(); ++o)
      EXPECT_EQ(std::memcmp(shared[o].data(), whole[o].data(), 8 * whole[o].size()), 0) << o;
    for (LocalPart& part : parts) {
      give_gas_forces(spec, part.state.loads, shared, forces);
      std::size_t compared = 0;
      for (const StepLoad& mine : part.state.loads)
        for (const StepLoad& load : whole_loads) {
          if (mine.name != load.name || mine.name.rfind(kGasLoadPrefix, 0) != 0) continue;
          EXPECT_TRUE(load.active);
          EXPECT_NE(load.work, 0.0);
          EXPECT_EQ(mine.work, load.work);
          for (const auto& [a, b] : {std::pair{&mine.surface.x, &load.surface.x},
                                     {&mine.surface.y, &load.surface.y},
                                     {&mine.surface.fx, &load.surface.fx},
                                     {&mine.surface.fy, &load.surface.fy}})
            EXPECT_TRUE(*a == *b);
          ++compared;
        }
      EXPECT_EQ(compared, whole_loads.size() - spec.loads.size());
    }
  }
}

TEST(GasOverRanks, TheOutlinesNodesThePartsHostAndTheForcesGivenThereAreTheWholeStates) {
  expect_the_gas_window_from_the_parts("cases/giordano_panel.toml", 300);
  expect_the_gas_window_from_the_parts("cases/shock_rod_gas.toml", 300);
}

}  // namespace
}  // namespace mpsolid
