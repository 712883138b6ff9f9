// Under mpirun at 2 and 3 ranks (ctest mpi_ranks_2, mpi_ranks_3): the
// communicator and the decomposition in real messages. A halo exchange of
// positions gives every rank's ghosts the serial run's values bit for bit,
// and the ordered sums' chunks, summed by their owners and gathered in rank
// order, add up to the serial sum's bits (docs/mpi.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

#include "kernels/model_registry.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/communicator.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/ordered_sum_parts.hpp"
#include "src/io/history_writer.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/gas_outlines.hpp"
#include "src/solver/rank_checks.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// The rod after some steps, the same on every rank (every rank steps it
// serially: the test is about the messages, not the decomposed step).
Simulation moved_rod() {
  Simulation sim(testing::rod_case({"l0=0.001"}));
  sim.advance(300);
  return sim;
}

TEST(Ranks, HaloExchangeGivesEveryGhostTheSerialValue) {
  const Communicator& world = Communicator::world();
  ASSERT_GE(world.size(), 2) << "run under mpirun with 2 or more ranks";
  Simulation sim = moved_rod();
  const ParticleStore& p = sim.particles();
  const Decomposition d = decompose(sim.state().bonds, world.size());
  const HaloPlan plan = plan_halo(sim.state().bonds, d, world.rank());
  // This rank's view: its own particles, everything else unknown (NaN).
  std::vector<double> x(p.size(), std::nan("")), y(p.size(), std::nan(""));
  const Range mine = d.owned(world.rank());
  for (std::size_t i = mine.begin; i < mine.end; ++i) {
    x[i] = p.x[i];
    y[i] = p.y[i];
  }
  std::vector<std::vector<double>> out;
  for (const auto& list : plan.send) {
    std::vector<double> message;
    for (const std::uint32_t i : list) message.insert(message.end(), {x[i], y[i]});
    out.push_back(std::move(message));
  }
  std::vector<std::vector<double>> in;
  for (const auto& list : plan.receive) in.emplace_back(2 * list.size());
  world.exchange(plan.peers, out, in);
  for (std::size_t k = 0; k < plan.peers.size(); ++k) {
    ASSERT_EQ(in[k].size(), 2 * plan.receive[k].size()) << "from rank " << plan.peers[k];
    for (std::size_t m = 0; m < plan.receive[k].size(); ++m) {
      x[plan.receive[k][m]] = in[k][2 * m];
      y[plan.receive[k][m]] = in[k][2 * m + 1];
    }
  }
  EXPECT_FALSE(plan.ghosts.empty());
  for (const std::uint32_t g : plan.ghosts)
    EXPECT_TRUE(same_bits(x[g], p.x[g]) && same_bits(y[g], p.y[g])) << "ghost " << g;
  // Every owned particle now sees all its partners.
  for (std::size_t i = mine.begin; i < mine.end; ++i)
    for (std::uint32_t k = sim.state().bonds.begin(i); k < sim.state().bonds.end(i); ++k)
      EXPECT_FALSE(std::isnan(x[sim.state().bonds.neighbor[k]]));
}

TEST(Ranks, SumPartsGatheredInRankOrderGiveTheSerialBits) {
  const Communicator& world = Communicator::world();
  Simulation sim = moved_rod();
  const ParticleStore& p = sim.particles();
  const auto term = [&](std::size_t i) {
    return std::array<double, 1>{(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i]) / p.inv_mass[i]};
  };
  const double serial = ordered_sum<1>(0, p.size(), term)[0];
  const Decomposition d = decompose(sim.state().bonds, world.size());
  // This rank's share of the serial chunks (a cut may fall inside one),
  // each rank's part after the other in rank order.
  std::vector<double> mine;
  ordered_sum_part<1>(0, p.size(), d.owned(world.rank()), term).append_to(mine);
  const std::vector<double> all = world.all_gather(mine);
  std::vector<OrderedSumPart<1>> parts;
  std::size_t at = 0;
  for (int r = 0; r < world.size(); ++r) parts.push_back(OrderedSumPart<1>::read(all, at));
  ASSERT_EQ(at, all.size());
  const double total = combine_ordered_sum(parts)[0];
  EXPECT_TRUE(same_bits(total, serial)) << total << " vs " << serial;
}

// The decomposed step: every rank steps its own slab of the rod (and the
// plate or the wall, where it owns them), exchanging its halos each
// step; the owned states gathered in rank order are the serial run's bits.
// `steps` decomposed steps of `spec` on this world, gathered in rank
// order, against the serial run's bits.
void expect_serial_bits(const CaseSpec& spec, std::int64_t steps) {
  const Communicator& world = Communicator::world();
  Simulation serial(spec);
  serial.advance(steps);
  Simulation base(spec);  // the same set-up on every rank
  // The case as the simulation fixed it (an automatic dt chosen).
  RankPart part = make_rank_part(base.spec(), base.state(), world);
  advance_rank_part(part, world, base.spec().dt, steps);
  const SolverState& local = part.local;
  const LocalLayout& layout = part.layout;
  EXPECT_EQ(local.step, steps);
  const ParticleStore& mine = local.particles;
  for (const StateArray& array : state_arrays(mine.dimension)) {
    const std::vector<double>& values = mine.*array.member;
    const std::vector<double> owned(values.begin() + static_cast<long>(layout.owned.begin),
                                    values.begin() + static_cast<long>(layout.owned.end));
    const std::vector<double> all = world.all_gather(owned);
    const std::vector<double>& expected = serial.particles().*array.member;
    ASSERT_EQ(all.size(), expected.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < all.size(); ++i) differ += !same_bits(all[i], expected[i]);
    EXPECT_EQ(differ, 0u) << array.name << ": particles that differ from the serial run";
  }
  // The bodies did move: the comparison is not of a state at rest.
  const std::vector<double>& vx = serial.particles().vx;
  EXPECT_TRUE(std::any_of(vx.begin(), vx.end(), [](double v) { return v != 0.0; }));
}

// A check's figures from the ranks' shares (src/solver/rank_checks.hpp):
// the motion sums, the largest speed, the loads' and drivers' work and the
// first non-finite particle, with the whole state's bits.
void expect_whole_state_check(const CaseSpec& spec, std::int64_t steps) {
  const Communicator& world = Communicator::world();
  Simulation serial(spec);
  serial.advance(steps);
  const SolverState& whole = serial.state();
  Simulation base(spec);
  RankPart part = make_rank_part(base.spec(), base.state(), world);
  advance_rank_part(part, world, base.spec().dt, steps);
  const Decomposition d = decompose_state(base.state(), world.size());
  const auto figures = [&] {
    std::vector<double> mine;
    append_rank_check(part, world, mine);
    // Each rank's share after the other: each share reads its own length.
    const std::vector<double> all = world.all_gather(mine);
    RankChecks checks(part.extent_ranges.size());
    std::size_t at = 0;
    SolverState copy = base.state();
    for (int r = 0; r < world.size(); ++r) checks.read(all, at, copy, d.pieces(r));
    EXPECT_EQ(at, all.size());
    return checks.finish(base.state(), d, {});
  };
  const CheckFigures f = figures();
  const Diagnostics expected = diagnostics_with_strain_energy(whole, 0.0);
  for (const auto& [name, got, want] :
       {std::tuple{"kinetic energy", f.diagnostics.kinetic_energy, expected.kinetic_energy},
        {"momentum x", f.diagnostics.momentum_x, expected.momentum_x},
        {"momentum y", f.diagnostics.momentum_y, expected.momentum_y},
        {"momentum z", f.diagnostics.momentum_z, expected.momentum_z},
        {"angular momentum x", f.diagnostics.angular_momentum_x, expected.angular_momentum_x},
        {"angular momentum y", f.diagnostics.angular_momentum_y, expected.angular_momentum_y},
        {"angular momentum", f.diagnostics.angular_momentum, expected.angular_momentum},
        {"damping loss", f.diagnostics.damping_loss, expected.damping_loss},
        {"max speed", f.diagnostics.max_speed, expected.max_speed},
        {"external work", f.diagnostics.external_work, expected.external_work}})
    EXPECT_TRUE(same_bits(got, want)) << name << ": " << got << " vs " << want;
  EXPECT_GT(expected.kinetic_energy, 0.0);
  // What a history row reads: the elastic bodies' extents, the probes, the
  // loads' work.
  const HistoryReadings readings = history_readings(whole, serial.spec());
  const auto same_values = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof a[0] * a.size()) == 0;
  };
  ASSERT_FALSE(readings.extents.empty());
  EXPECT_TRUE(same_values(f.readings.extents, readings.extents));
  EXPECT_TRUE(same_values(f.readings.probes, readings.probes));
  EXPECT_EQ(readings.probes.size(), whole.probes.size());
  EXPECT_TRUE(same_values(f.readings.load_work, readings.load_work));
  const Fastest fastest = fastest_moving(whole.particles);
  EXPECT_EQ(f.fastest.particle, fastest.particle);
  EXPECT_TRUE(same_bits(f.fastest.speed2, fastest.speed2));
  EXPECT_TRUE(f.finite.ok);
  // Two particles gone bad on different ranks: the first in storage order.
  const std::size_t n = whole.particles.size();
  for (const std::size_t bad : {n - 2, n / 3 + 1}) {
    const LocalLayout& layout = part.layout;
    if (layout.owns(bad)) part.local.particles.vx[layout.local_of_owned(bad)] = std::nan("");
  }
  const CheckFigures broken = figures();
  EXPECT_FALSE(broken.finite.ok);
  EXPECT_EQ(broken.finite.particle, n / 3 + 1);
}

TEST(Ranks, ACheckFromTheRanksSharesHasTheWholeStatesFigures) {
  set_thread_count(1);
  // The rod: walls first (the motion sums start after them), the plate a
  // rigid body under a force, probes in the rod's first and last rows (on
  // different ranks).
  expect_whole_state_check(testing::rod_case({"l0=0.001", "probes.near.at=[0.001, -0.019]",
                                              "probes.far.at=[0.099, 0.019]"}),
                           300);
  // In space: a spinning cube cut across the ranks, every momentum a vector.
  expect_whole_state_check(
      load_case(testing::source_path("cases/spinning_cube.toml"), {"l0=0.008"}), 100);
}

// A gas window's outline nodes over ranks (src/solver/gas_outlines.hpp):
// after decomposed steps, the nodes' positions and velocities every rank
// shares are those of the whole state the ranks' owned particles make, bit
// for bit (the ghosts, which the steps leave a step behind, brought up to
// date first): the rod's, the thrown plate's and the wall's.
TEST(Ranks, TheGasOutlinesNodesSharedAfterDecomposedStepsAreTheWholeStates) {
  set_thread_count(1);
  const Communicator& world = Communicator::world();
  Simulation base(
      load_case(testing::source_path("cases/shock_rod_gas.toml"),
                {"l0=0.004", "bodies.plate.velocity=[30.0, -10.0]", "bodies.plate.spin=400.0"}));
  const CaseSpec& spec = base.spec();
  RankPart part = make_rank_part(spec, base.state(), world);
  advance_rank_part(part, world, spec.dt, 200);
  SolverState whole = base.state();
  const LocalLayout& layout = part.layout;
  for (std::vector<double> ParticleStore::*member :
       {&ParticleStore::x, &ParticleStore::y, &ParticleStore::vx, &ParticleStore::vy}) {
    const std::vector<double>& mine = part.local.particles.*member;
    whole.particles.*member =
        world.all_gather(std::vector<double>(mine.begin() + static_cast<long>(layout.owned.begin),
                                             mine.begin() + static_cast<long>(layout.owned.end)));
  }
  const OutlineMotion expected =
      outline_motion(whole.particles, gas_outlines(spec, whole.body_ranges));
  const OutlineMotion at_start =
      outline_motion(base.state().particles, gas_outlines(spec, whole.body_ranges));
  const OutlineMotion shared = shared_outline_motion(
      part, part_gas_outlines(spec, part.local.loads, part.body_ranges, layout), world);
  ASSERT_EQ(shared.size(), 3u);  // the rod, the plate, the wall
  ASSERT_EQ(expected.size(), 3u);
  for (std::size_t o = 0; o < 3; ++o) {
    ASSERT_EQ(shared[o].size(), expected[o].size());
    EXPECT_EQ(std::memcmp(shared[o].data(), expected[o].data(), 8 * expected[o].size()), 0)
        << "outline " << o;
    if (o < 2) {
      EXPECT_NE(expected[o], at_start[o]) << "outline " << o << " moved";
    }
  }
}

TEST(Ranks, DecomposedStepGivesTheSerialBits) {
  set_thread_count(1);
  for (const std::string& model : model_names()) {
    SCOPED_TRACE(model);
    expect_serial_bits(testing::rod_case({"l0=0.001", "model=" + model}), 3000);
  }
}

// In space: a spinning cube cut across the ranks, falling under gravity, a
// ramped force and a ramped pressure on its top, damped, with every model (the paper models turn a
// quaternion per particle).
TEST(Ranks, DecomposedStepInSpaceGivesTheSerialBits) {
  set_thread_count(1);
  for (const std::string& model : model_names()) {
    SCOPED_TRACE(model);
    expect_serial_bits(
        load_case(testing::source_path("cases/spinning_cube.toml"),
                  {"l0=0.008", "model=" + model, "loads.g.type=\"acceleration\"",
                   "loads.g.body=\"cube\"", "loads.g.acceleration=[1.0, 2.0, -9.81]",
                   "loads.push.body=\"cube\"", "loads.push.force=[0.5, 0.0, 1.0]",
                   "loads.push.history=\"ramp\"", "loads.push.rise_time=0.002",
                   "damping.coefficient=20.0", "damping.end=0.01", "loads.blast.type=\"pressure\"",
                   "loads.blast.body=\"cube\"", "loads.blast.pressure=2e3",
                   "loads.blast.half_space={ point = [0.0, 0.0, 0.02], normal = "
                   "[0.0, 0.3, 1.0] }",
                   "loads.blast.history=\"ramp\"", "loads.blast.rise_time=0.005"}),
        300);
  }
}

// Contact in space: two spheres colliding obliquely, cut across the ranks.
TEST(Ranks, DecomposedContactInSpaceGivesTheSerialBits) {
  set_thread_count(1);
  expect_serial_bits(load_case(testing::source_path("cases/colliding_spheres.toml")), 500);
}

// Rigid bodies in space, each kept whole on a rank: the struck sphere made
// rigid (in the paper's model its particles spin with it), and the brick
// tumbling alone.
TEST(Ranks, DecomposedRigidBodiesInSpaceGiveTheSerialBits) {
  set_thread_count(1);
  for (const char* model : {"finite_strain", "paper"}) {
    SCOPED_TRACE(model);
    expect_serial_bits(
        load_case(testing::source_path("cases/colliding_spheres.toml"),
                  {"bodies.b.kind=\"rigid\"", std::string("model=\"") + model + "\""}),
        500);
  }
  expect_serial_bits(load_case(testing::source_path("cases/tumbling_brick.toml")), 300);
}

// A ramped pressure on the plate's face: the plate takes the pressure's
// forces; the rod, cut across the ranks, the plate's push.
TEST(Ranks, DecomposedPressureGivesTheSerialBits) {
  set_thread_count(1);
  expect_serial_bits(
      load_case(testing::source_path("cases/shock_rod_pressure.toml"),
                {"l0=0.001", "loads.shock.history=\"ramp\"", "loads.shock.rise_time=5e-6"}),
      2000);
}

// A blast on one disk, cut across the ranks: each rank positions the
// pressure's nodes it hosts and the ranks share them.
TEST(Ranks, APressuresBodyCutAcrossRanksGivesTheSerialBits) {
  set_thread_count(1);
  expect_serial_bits(load_case(testing::source_path("cases/disk_blast.toml")), 300);
}

// Driven grips, each kept whole on a rank, stretching a holed plate cut
// across the ranks.
TEST(Ranks, DecomposedPrescribedMotionGivesTheSerialBits) {
  set_thread_count(1);
  expect_serial_bits(load_case(testing::source_path("cases/holed_plate_grips.toml"), {"l0=0.001"}),
                     400);
}

// Contact over ranks: the two blocks of cases/colliding_blocks.toml (l0 =
// 0.5 mm, seven chunks: every rank owns some) through their collision,
// with the list rebuilt many times. Each rank's own candidates get the
// serial forces, so the gathered states are the serial run's bits; the
// pairs across ranks came through the contact halo (leaving it out fails).
TEST(Ranks, DecomposedContactGivesTheSerialBits) {
  const Communicator& world = Communicator::world();
  set_thread_count(1);
  const CaseSpec spec =
      load_case(testing::source_path("cases/colliding_blocks.toml"), {"l0=0.0005"});
  Simulation serial(spec);
  const std::int64_t steps = static_cast<std::int64_t>(std::llround(1.6e-3 / serial.spec().dt));
  serial.advance(steps);
  Simulation base(spec);
  RankPart part = make_rank_part(base.spec(), base.state(), world);
  advance_rank_part(part, world, base.spec().dt, steps);
  const LocalLayout& layout = part.layout;
  for (const StateArray& array : state_arrays(2)) {
    const std::vector<double>& values = part.local.particles.*array.member;
    const std::vector<double> all =
        world.all_gather(std::vector<double>(values.begin() + static_cast<long>(layout.owned.begin),
                                             values.begin() + static_cast<long>(layout.owned.end)));
    const std::vector<double>& expected = serial.particles().*array.member;
    ASSERT_EQ(all.size(), expected.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < all.size(); ++i) differ += !same_bits(all[i], expected[i]);
    EXPECT_EQ(differ, 0u) << array.name << ": particles that differ from the serial run";
  }
  // The blocks did collide, across ranks, through rebuilds.
  const std::vector<double> facts = world.all_gather(
      {static_cast<double>(part.contact.halo.peers.size()),
       static_cast<double>(part.local.contact.rebuilds), part.halo_cost.bytes_sent});
  double peers = 0;
  for (std::size_t r = 0; r < facts.size(); r += 3) peers += facts[r];
  EXPECT_GT(peers, 0.0) << "no rank needed another's candidates";
  EXPECT_GT(facts[1], 5.0) << "rebuilds";
  const Diagnostics d = serial.diagnostics();
  EXPECT_GT(d.contact_energy, 0.0) << "the blocks are in contact at the end";
}

}  // namespace
}  // namespace mpsolid

int main(int argc, char** argv) {
  mpsolid::MpiSession mpi(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  // One report: rank 0's (a failure on another rank still fails its exit code).
  if (mpsolid::Communicator::world().rank() != 0) {
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  return RUN_ALL_TESTS();
}
