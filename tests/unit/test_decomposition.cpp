// The decomposition over ranks (docs/mpi.md), checked in one process:
// contiguous ranges that cover every particle once and balance the work
// to within a particle's, and halo plans in which every rank's ghosts are exactly the
// partners it does not own, and what one rank sends another is what the
// other expects to receive.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include <cstring>

#include "kernels/model_registry.hpp"
#include "src/core/half_angles.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/part_message.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/setup.hpp"
#include "src/solver/simulation.hpp"
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

TEST(Decomposition, RangesCoverEverythingAndBalanceTheWork) {
  const BondTable bonds = rod_bonds("0.0005");  // 18,080 particles
  const std::size_t n = bonds.particle_count();
  const double total = work_of(bonds, {0, n});
  double particle_work = 0;  // the most of one particle
  for (std::size_t i = 0; i < n; ++i)
    particle_work = std::max(particle_work, work_of(bonds, {i, i + 1}));
  for (int ranks = 1; ranks <= 8; ++ranks) {
    SCOPED_TRACE(ranks);
    const Decomposition d = decompose(bonds, ranks);
    ASSERT_EQ(d.ranks(), ranks);
    EXPECT_EQ(d.starts.front(), 0u);
    EXPECT_EQ(d.starts.back(), n);
    for (int r = 0; r < ranks; ++r) {
      const Range mine = d.owned(r);
      EXPECT_LE(mine.begin, mine.end);
      // Each cut within half a particle's work of its target.
      EXPECT_NEAR(work_of(bonds, mine), total / ranks, particle_work);
      for (std::size_t i = mine.begin; i < mine.end; i += 97) EXPECT_EQ(d.owner_of(i), r);
    }
  }
  // More ranks than particles: some own nothing, every particle still has
  // one owner.
  const BondTable small = rod_bonds("0.004");  // 300 particles
  const int many = 400;
  const Decomposition d = decompose(small, many);
  std::size_t owned = 0, empty = 0;
  for (int r = 0; r < many; ++r) {
    owned += d.owned(r).size();
    empty += d.owned(r).empty() ? 1 : 0;
  }
  EXPECT_GE(empty, 100u);
  EXPECT_EQ(owned, small.particle_count());
  for (std::size_t i = 0; i < small.particle_count(); ++i) {
    const Range r = d.owned(d.owner_of(i));
    EXPECT_TRUE(i >= r.begin && i < r.end) << i;
  }
}

// A rigid or loaded body is never cut: at 0.25 mm the rod's plate is
// 6,000 particles, and sixteen ranks would split it.
TEST(Decomposition, BodiesKeptWholeAreNeverCut) {
  PhaseTimers timers;
  const SolverState s = set_up(testing::rod_case({"l0=0.00025"}), timers);
  const Range plate = s.body_ranges.at(0);  // bodies in name order: plate, rod, wall
  ASSERT_GT(plate.size(), 5000u);
  const Decomposition free = decompose(s.bonds, 16);
  bool cut_before = false;
  for (const std::size_t start : free.starts)
    cut_before |= start > plate.begin && start < plate.end;
  EXPECT_TRUE(cut_before) << "the plain decomposition should cut the plate here";
  const Decomposition kept = decompose(s.bonds, 16, {plate});
  for (const std::size_t start : kept.starts) {
    EXPECT_FALSE(start > plate.begin && start < plate.end) << start;
  }
  EXPECT_EQ(kept.starts.back(), s.bonds.particle_count());
  EXPECT_TRUE(std::is_sorted(kept.starts.begin(), kept.starts.end()));
}

// The cut from the particle count alone (no bond table): the cut of unit
// costs, balanced to within a particle, a body kept whole moved to its start.
TEST(Decomposition, TheCutFromTheCountIsTheCutOfUnitCosts) {
  for (const std::size_t n : {0u, 1u, 7u, 1000u, 123457u})
    for (const int ranks : {1, 2, 3, 5, 16}) {
      const Range whole{n / 3, n / 3 + n / 4};
      for (const std::vector<Range>& keep : {std::vector<Range>{}, std::vector<Range>{whole}}) {
        const Decomposition d = decompose_count(n, ranks, keep);
        EXPECT_EQ(d.starts, decompose_costs(std::vector<double>(n, 1.0), ranks, keep).starts)
            << n << " particles, " << ranks << " ranks";
        ASSERT_EQ(d.starts.size(), static_cast<std::size_t>(ranks) + 1);
        EXPECT_EQ(d.starts.front(), 0u);
        EXPECT_EQ(d.starts.back(), n);
        for (int r = 0; r < ranks; ++r) {
          const Range mine = d.owned(r);
          if (keep.empty()) {
            // Balanced to within one particle either way of n / ranks.
            EXPECT_LE(std::abs(static_cast<double>(mine.size()) - static_cast<double>(n) / ranks),
                      1.0);
          } else {
            EXPECT_FALSE(mine.begin > whole.begin && mine.begin < whole.end) << mine.begin;
          }
        }
      }
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

// A rank's local copy keeps every owned particle's bond row (same partners,
// same order, same reference vectors) and gives each ghost its bonds to
// owned particles.
TEST(Decomposition, LocalStateKeepsTheOwnedRowsAndTheGhostsBondsToThem) {
  PhaseTimers timers;
  const SolverState global = set_up(testing::rod_case({"l0=0.001"}), timers);
  const BondTable& bonds = global.bonds;
  for (int ranks : {2, 3, 5}) {
    const Decomposition d = decompose(bonds, ranks);
    for (int r = 0; r < ranks; ++r) {
      SCOPED_TRACE(::testing::Message() << r << " of " << ranks);
      const LocalLayout layout = local_layout(d, plan_halo(bonds, d, r), r);
      ASSERT_TRUE(std::is_sorted(layout.global_of.begin(), layout.global_of.end()));
      ASSERT_EQ(layout.owned.size(), d.owned(r).size());
      if (!layout.owned.empty()) {
        EXPECT_EQ(layout.global_of[layout.owned.begin], d.owned(r).begin);
      }
      const ParticleStore local = local_particles(global.particles, layout);
      const BondTable lb = local_bonds(bonds, local, layout);
      for (std::size_t k = 0; k < layout.size(); ++k) {
        const std::size_t g = layout.global_of[k];
        EXPECT_EQ(local.kind[k], global.particles.kind[g]);
        std::vector<std::uint32_t> expected;
        std::vector<double> r0x;
        const bool owned = k >= layout.owned.begin && k < layout.owned.end;
        for (std::uint32_t b = bonds.begin(g); b < bonds.end(g); ++b)
          if (owned || d.owner_of(bonds.neighbor[b]) == r) {
            expected.push_back(bonds.neighbor[b]);
            r0x.push_back(bonds.r0x[b]);
          }
        std::vector<std::uint32_t> got;
        for (std::uint32_t b = lb.begin(k); b < lb.end(k); ++b) {
          got.push_back(layout.global_of[lb.neighbor[b]]);
          EXPECT_EQ(std::memcmp(&lb.r0x[b], &r0x[b - lb.begin(k)], sizeof(double)), 0);
        }
        EXPECT_EQ(got, expected) << "row of global particle " << g;
      }
    }
  }
}

// Calls check(layout, its particles, its bond table) for every rank's local
// state of `global` cut for 2 and for 3 ranks.
template <class Check>
void for_each_rank_part(const SolverState& global, Check&& check) {
  for (int ranks : {2, 3}) {
    const Decomposition d = decompose(global.bonds, ranks);
    for (int r = 0; r < ranks; ++r) {
      SCOPED_TRACE(::testing::Message() << r << " of " << ranks);
      const LocalLayout layout = local_layout(d, plan_halo(global.bonds, d, r), r);
      ParticleStore local = local_particles(global.particles, layout);
      const BondTable lb = local_bonds(global.bonds, local, layout);
      check(layout, local, lb);
    }
  }
}

// The decomposed step's kernels, one rank at a time: with the ghosts'
// positions and half angles (the first halo), the paper models' strain pass
// gives the owned particles the serial pressure bit for bit; with the
// ghosts' pressure (the second halo), the force pass the serial forces.
TEST(Decomposition, PaperModelPassesOnALocalStateGiveTheSerialBits) {
  for (const std::string model : {"paper", "paper_conservative"}) {
    SCOPED_TRACE(model);
    Simulation sim(testing::rod_case({"l0=0.001", "model=" + model}));
    sim.advance(400);  // moving, rotated, loaded
    sim.refresh_fields();
    const SolverState& global = sim.state();
    ParticleStore serial = global.particles;
    AnyModel serial_model = make_model(model, serial, global.bonds, sim.spec().model_options);
    std::visit(
        [&](auto& m) {
          m.compute_strain(serial, global.bonds, serial.all());
          m.compute_forces(serial, global.bonds, serial.moving());
        },
        serial_model);
    for_each_rank_part(
        global, [&](const LocalLayout& layout, ParticleStore& local, const BondTable& lb) {
          AnyModel local_model = make_model(model, local, lb, sim.spec().model_options);
          std::visit([&](auto& m) { m.compute_strain(local, lb, layout.owned); }, local_model);
          for (std::size_t k = layout.owned.begin; k < layout.owned.end; ++k)
            ASSERT_EQ(std::memcmp(&local.pressure[k], &serial.pressure[layout.global_of[k]],
                                  sizeof(double)),
                      0)
                << "pressure of global particle " << layout.global_of[k];
          // The second halo: the ghosts' pressure from their owners.
          for (std::size_t k = 0; k < layout.size(); ++k)
            if (k < layout.owned.begin || k >= layout.owned.end)
              local.pressure[k] = serial.pressure[layout.global_of[k]];
          const Range moving_owned{std::max(layout.owned.begin, local.moving().begin),
                                   std::min(layout.owned.end, local.moving().end)};
          std::visit([&](auto& m) { m.compute_forces(local, lb, moving_owned); }, local_model);
          for (std::size_t k = moving_owned.begin; k < moving_owned.end; ++k) {
            const std::size_t g = layout.global_of[k];
            ASSERT_EQ(std::memcmp(&local.fx[k], &serial.fx[g], sizeof(double)), 0) << g;
            ASSERT_EQ(std::memcmp(&local.fy[k], &serial.fy[g], sizeof(double)), 0) << g;
            ASSERT_EQ(std::memcmp(&local.torque[k], &serial.torque[g], sizeof(double)), 0) << g;
          }
        });
  }
}

// The same for the corrected-gradient models, whose passes need three
// halos: with the ghosts' positions, pass 1 gives every owned particle the
// serial F; with the ghosts' F, the gaps and pass 1b the serial
// (S + Q) A^-1; with the ghosts' (S + Q) A^-1 the force pass the serial
// forces (leaving out either of the last two fails). A ghost's A^-1 (its
// local row is partial) is never read.
template <class Model>
void check_corrected_gradient_passes() {
  {
    const std::string model = Model::name;
    SCOPED_TRACE(model);
    Simulation sim(testing::rod_case({"l0=0.001", "model=" + model}));
    sim.advance(400);  // moving and loaded
    const SolverState& global = sim.state();
    ParticleStore serial = global.particles;
    AnyModel serial_any = make_model(model, serial, global.bonds, sim.spec().model_options);
    auto& serial_model = std::get<Model>(serial_any);
    serial_model.compute_strain(serial, global.bonds, serial.all());
    serial_model.compute_forces(serial, global.bonds, serial.moving());
    for_each_rank_part(global, [&](const LocalLayout& layout, ParticleStore& local,
                                   const BondTable& lb) {
      AnyModel local_any = make_model(model, local, lb, sim.spec().model_options, layout.owned);
      auto& m = std::get<Model>(local_any);
      const auto is_ghost = [&](std::size_t k) {
        return k < layout.owned.begin || k >= layout.owned.end;
      };
      // A halo of one field: the ghosts' values from the serial model's.
      const auto halo = [&](ParticleField to, ParticleField from) {
        for (std::size_t k = 0; k < layout.size(); ++k)
          if (is_ghost(k))
            for (std::size_t c = 0; c < to.width; ++c)
              to.at(k, c) = from.at(layout.global_of[k], c);
      };
      const auto owned_match = [&](ParticleField got, ParticleField want, const char* what) {
        for (std::size_t k = layout.owned.begin; k < layout.owned.end; ++k)
          for (std::size_t c = 0; c < got.width; ++c)
            ASSERT_EQ(std::memcmp(&got.at(k, c), &want.at(layout.global_of[k], c), sizeof(double)),
                      0)
                << what << " of global particle " << layout.global_of[k] << ", component " << c;
      };
      m.compute_deformation_gradient(local, lb, layout.owned);
      owned_match(m.deformation_gradient_field(), serial_model.deformation_gradient_field(), "F");
      halo(m.deformation_gradient_field(), serial_model.deformation_gradient_field());
      m.compute_hourglass_stress(local, lb, layout.owned);
      owned_match(m.stress_field(), serial_model.stress_field(), "(S + Q) A^-1");
      halo(m.stress_field(), serial_model.stress_field());
      const Range moving_owned{std::max(layout.owned.begin, local.moving().begin),
                               std::min(layout.owned.end, local.moving().end)};
      m.compute_forces(local, lb, moving_owned);
      for (std::size_t k = moving_owned.begin; k < moving_owned.end; ++k) {
        const std::size_t g = layout.global_of[k];
        ASSERT_EQ(std::memcmp(&local.fx[k], &serial.fx[g], sizeof(double)), 0) << g;
        ASSERT_EQ(std::memcmp(&local.fy[k], &serial.fy[g], sizeof(double)), 0) << g;
      }
    });
  }
}
TEST(Decomposition, CorrectedGradientPassesOnALocalStateGiveTheSerialBits) {
  check_corrected_gradient_passes<FiniteStrainModel>();
  check_corrected_gradient_passes<LinearElasticModel>();
}

// Rank 0 sends each follower its part as a stream of pieces: what arrives
// is what was sent, every array bit for bit (the contact case: rigid plate,
// load, walls, candidates; the fine rod: a message of several pieces).
TEST(Decomposition, APartSentInPiecesArrivesWhole) {
  const auto same = [](const auto& a, const auto& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
  };
  for (const auto& [path, l0] : {std::pair{"cases/shock_rod_55kN.toml", "0.002"},
                                 std::pair{"cases/shock_rod.toml", "0.000125"}}) {
    SCOPED_TRACE(path);
    Simulation sim(load_case(testing::source_path(path), {std::string("l0=") + l0}));
    const SolverState& global = sim.state();
    const Decomposition d = decompose(global.bonds, 3);
    // The rank holding the plate (and its load), where there is one.
    const int rank =
        global.rigid_bodies.empty() ? 1 : d.owner_of(global.rigid_bodies.front().range.begin);
    const LocalPart sent = local_part(global, d, rank);
    std::vector<std::vector<double>> pieces;
    pack_local_part(sent, [&](const std::vector<double>& piece) { pieces.push_back(piece); });
    std::size_t next = 0;
    const LocalPart got = unpack_local_part([&] { return pieces.at(next++); });
    EXPECT_EQ(next, pieces.size()) << "every piece read";
    std::size_t values = 0;
    for (const auto& piece : pieces) values += piece.size();
    if (std::string(l0) == "0.000125") {
      EXPECT_GT(pieces.size(), 2u) << values << " values";
    }
    EXPECT_EQ(got.decomposition.starts, sent.decomposition.starts);
    EXPECT_EQ(got.layout.global_of, sent.layout.global_of);
    EXPECT_EQ(got.layout.owned.begin, sent.layout.owned.begin);
    ASSERT_EQ(got.layout.owned_pieces.size(), sent.layout.owned_pieces.size());
    for (std::size_t k = 0; k < got.layout.owned_pieces.size(); ++k) {
      EXPECT_EQ(got.layout.owned_pieces[k].begin, sent.layout.owned_pieces[k].begin);
      EXPECT_EQ(got.layout.owned_pieces[k].end, sent.layout.owned_pieces[k].end);
    }
    EXPECT_EQ(got.halo.peers, sent.halo.peers);
    EXPECT_EQ(got.halo.send, sent.halo.send);
    EXPECT_EQ(got.halo.receive, sent.halo.receive);
    const ParticleStore &a = got.state.particles, &b = sent.state.particles;
    for_each_particle_member([&](const auto& info, auto member) {
      EXPECT_TRUE(same(a.*member, b.*member)) << info.name;
    });
    EXPECT_EQ(a.elastic.begin, b.elastic.begin);
    EXPECT_EQ(a.rigid.end, b.rigid.end);
    const BondTable &ga = got.state.bonds, &gb = sent.state.bonds;
    EXPECT_EQ(ga.offsets, gb.offsets);
    EXPECT_EQ(ga.neighbor, gb.neighbor);
    EXPECT_TRUE(same(ga.r0x, gb.r0x));
    EXPECT_TRUE(same(ga.r0y, gb.r0y));
    EXPECT_EQ(ga.hash(), gb.hash());
    ASSERT_EQ(got.state.rigid_bodies.size(), sent.state.rigid_bodies.size());
    for (std::size_t k = 0; k < got.state.rigid_bodies.size(); ++k) {
      const RigidBody &x = got.state.rigid_bodies[k], &y = sent.state.rigid_bodies[k];
      EXPECT_EQ(x.name, y.name);
      EXPECT_EQ(x.range.begin, y.range.begin);
      EXPECT_TRUE(same(std::vector<double>{x.xg0, x.xg, x.omega, x.orbital_inertia, x.mass_total},
                       std::vector<double>{y.xg0, y.xg, y.omega, y.orbital_inertia, y.mass_total}));
      EXPECT_TRUE(same(x.dx0, y.dx0));
    }
    ASSERT_EQ(got.state.loads.size(), sent.state.loads.size());
    for (std::size_t k = 0; k < got.state.loads.size(); ++k) {
      EXPECT_EQ(got.state.loads[k].name, sent.state.loads[k].name);
      EXPECT_EQ(got.state.loads[k].first_step, sent.state.loads[k].first_step);
      EXPECT_EQ(got.state.loads[k].fx, sent.state.loads[k].fx);
    }
    EXPECT_EQ(got.state.holds.size(), sent.state.holds.size());
    const ContactState &ca = got.state.contact, &cb = sent.state.contact;
    EXPECT_EQ(ca.candidates, cb.candidates);
    EXPECT_EQ(ca.group, cb.group);
    EXPECT_EQ(ca.first_moving, cb.first_moving);
    EXPECT_EQ(ca.parameters.stiffness, cb.parameters.stiffness);
    EXPECT_EQ(ca.force_x.size(), cb.force_x.size());
    if (std::string(path) == "cases/shock_rod_55kN.toml") {
      EXPECT_TRUE(ca.enabled());
      EXPECT_FALSE(got.state.loads.empty() || got.state.rigid_bodies.empty())
          << "the part holds the plate and its load";
    }
    // A message cut short is an error, not a partial part.
    pieces.back().pop_back();
    next = 0;
    EXPECT_THROW(unpack_local_part([&]() -> std::vector<double> {
                   if (next == pieces.size()) return {};
                   return pieces.at(next++);
                 }),
                 std::logic_error);
  }
}

}  // namespace
}  // namespace mpsolid
