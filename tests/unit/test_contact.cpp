// Contact (MODEL.md section 8): the pair force against a plain all-pairs
// reference, the candidates, the Verlet list's validity, and collisions:
// blocks that rebound instead of passing through each other, conserving
// momentum and angular momentum to round-off and energy to O(dt), the same
// bits at 1, 2 and 3 threads and after a resume, through many list rebuilds.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "kernels/contact_force.hpp"
#include "neighbor/contact_search.hpp"
#include "src/core/parallel.hpp"
#include "src/io/checkpoint.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

// A finite_strain case at l0 = 1 mm with rubber, the given bodies and
// contact on (with extra [contact] keys), run for 2 ms at dt (TOML text).
std::string contact_case(const std::string& bodies, const std::string& dt,
                         const std::string& contact = "") {
  return fmt::format(R"(model = "finite_strain"
l0 = 0.001

[materials.rubber]
E = 2.8e6
nu = 0.45
rho = 1010.0
{}
[contact]
enabled = true
{}
[time]
dt = {}
end = 0.002

[output]
frame_interval = 1.0e-4
)",
                     bodies, contact, dt);
}

// Two 8 x 8 rubber blocks flying at each other at 10 m/s; `offset` shifts
// the right one up (m) for an oblique hit, `spin` spins it (rad/s).
std::string blocks_toml(double offset = 0.0, double spin = 0.0, const std::string& dt = "2e-7",
                        const std::string& contact = "") {
  return contact_case(fmt::format(R"(
[bodies.left]
kind = "elastic"
material = "rubber"
x = [0.0, 0.008]
y = [0.0, 0.008]
velocity = [10.0, 0.0]

[bodies.right]
kind = "elastic"
material = "rubber"
x = [0.012, 0.020]
y = [{}, {}]
velocity = [-10.0, 0.0]
spin = {}
)",
                                  offset, 0.008 + offset, spin),
                      dt, contact);
}

// An 8 x 8 block falling at 5 m/s onto a wall 3 rows thick.
std::string drop_toml(const std::string& dt) {
  return contact_case(R"(
[bodies.block]
kind = "elastic"
material = "rubber"
x = [0.006, 0.014]
y = [0.006, 0.014]
velocity = [0.0, -5.0]

[bodies.floor]
kind = "wall"
material = "rubber"
x = [0.0, 0.020]
y = [0.0, 0.003]
)",
                      dt);
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

double total_energy(const Diagnostics& d) {
  return d.kinetic_energy + d.strain_energy + d.contact_energy;
}

// Mean velocity of a body's particles (equal masses: its centre of mass).
std::array<double, 2> body_velocity(Simulation& sim, std::size_t body) {
  const Range r = sim.state().body_ranges[body];
  double vx = 0, vy = 0;
  for (std::size_t i = r.begin; i < r.end; ++i) {
    vx += sim.particles().vx[i];
    vy += sim.particles().vy[i];
  }
  return {vx / static_cast<double>(r.size()), vy / static_cast<double>(r.size())};
}

TEST(Contact, PairForcesMatchAPlainAllPairsSumAndTheEnergyGradient) {
  Simulation sim(load_case_text(blocks_toml(0.003), "blocks.toml"));
  ParticleStore& p = sim.state_to_change().particles;
  ContactState& c = sim.state_to_change().contact;
  ASSERT_TRUE(c.enabled());
  // Push the right block into the left one: many pairs closer than d.
  const Range right = sim.state().body_ranges[1];
  for (std::size_t i = right.begin; i < right.end; ++i) p.x[i] -= 4.3e-3;  // 0.7 l0 apart
  build_contact_list(c, p, sim.state().bonds);
  compute_contact_forces(c, p, {0, c.size()}, 0);
  const double k = c.parameters.stiffness, d = c.parameters.distance;
  int touching = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const std::size_t i = c.candidates[a];
    double fx = 0, fy = 0;
    for (std::size_t b = 0; b < c.size(); ++b) {  // every other candidate, ascending
      const std::size_t j = c.candidates[b];
      if (j == i || p.body[j] == p.body[i]) continue;  // these blocks have no self-contact yet
      const double dx = p.x[i] - p.x[j], dy = p.y[i] - p.y[j];
      const double r = std::sqrt(dx * dx + dy * dy);
      if (r >= d) continue;
      ++touching;
      fx += k * (d - r) / r * dx;
      fy += k * (d - r) / r * dy;
    }
    EXPECT_TRUE(same_bits(c.force_x[a], fx) && same_bits(c.force_y[a], fy)) << "particle " << i;
  }
  EXPECT_GE(touching, 10);  // 5 rows overlap: 5 pairs, each seen from both ends
  // The force is minus the gradient of the contact energy (central differences).
  std::size_t a = c.candidates_in({right.begin, right.end}).begin;
  while (a < c.size() && c.force_x[a] == 0.0) ++a;
  ASSERT_LT(a, c.size());
  const std::size_t i = c.candidates[a];
  const auto energy = [&] {
    double e = 0;
    for (std::size_t b = 0; b < c.size(); ++b) e += contact_energy_share(c, p, b);
    return e;
  };
  const double h = 1e-9, x = p.x[i];
  p.x[i] = x + h;
  const double plus = energy();
  p.x[i] = x - h;
  const double minus = energy();
  p.x[i] = x;
  EXPECT_NEAR(-(plus - minus) / (2 * h), c.force_x[a], 1e-6 * std::abs(c.force_x[a]) + 1e-3);
  EXPECT_NE(c.force_x[a], 0.0);
}

TEST(Contact, ClosestPairIsTheAllPairsMinimumOfPairsThatMayTouch) {
  Simulation sim(load_case_text(drop_toml("2e-7"), "drop.toml"));
  const ParticleStore& p = sim.particles();
  const ContactState& c = sim.state().contact;
  const BondTable& bonds = sim.state().bonds;
  const auto brute_force = [&] {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < c.size(); ++a)
      for (std::size_t b = a + 1; b < c.size(); ++b) {
        const std::size_t i = c.candidates[a], j = c.candidates[b];
        if (p.kind[i] == Kind::wall && p.kind[j] == Kind::wall) continue;
        if (std::find(bonds.neighbor.begin() + bonds.begin(i),
                      bonds.neighbor.begin() + bonds.end(i),
                      j) != bonds.neighbor.begin() + bonds.end(i))
          continue;
        best = std::min(best, std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]));
      }
    return best;
  };
  // At rest: the block's own surface pairs two sites along and one across.
  ClosestContact closest = closest_contact(c, p, bonds, 0.01);
  ASSERT_TRUE(closest.found);
  EXPECT_NEAR(closest.distance, std::sqrt(5.0) * 1e-3, 1e-15);
  EXPECT_NEAR(closest.distance, brute_force(), 1e-15);
  EXPECT_EQ(p.body[closest.i], p.body[closest.j]);
  // On the floor: the block's bottom and the floor's top row (the state
  // brought back from the threads' parts, which step as ranks).
  sim.advance(4000);
  sim.state();
  closest = closest_contact(c, p, bonds, 0.01);
  ASSERT_TRUE(closest.found);
  EXPECT_NEAR(closest.distance, brute_force(), 1e-15);
  EXPECT_NE(p.body[closest.i], p.body[closest.j]);
  EXPECT_LT(closest.distance, 1.2e-3);
  EXPECT_FALSE(closest_contact(c, p, bonds, 0.5 * closest.distance).found);
}

// Self-contact: a strip folded so that its two ends meet repels its own
// particles (they are not bonded: 30 sites apart at set-up), and only them.
TEST(Contact, ABodyFoldedOntoItselfRepelsItsOwnParticles) {
  const std::string strip = R"(
[bodies.strip]
kind = "elastic"
material = "rubber"
x = [0.0, 0.030]
y = [0.0, 0.003]
)";
  Simulation sim(load_case_text(contact_case(strip, "2e-7"), "strip.toml"));
  ParticleStore& p = sim.state_to_change().particles;
  ContactState& c = sim.state_to_change().contact;
  ASSERT_EQ(c.size(), p.size());  // three rows: every particle is on the surface
  // Fold it: the right half turned over onto the left, its top row 0.8 l0
  // above the left half's top row.
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.x0[i] > 0.015) {
      p.x[i] = 0.030 - p.x0[i];
      p.y[i] = 0.0058 - p.y0[i];  // top row (y0 = 2.5 mm) to 3.3 mm
    }
  build_contact_list(c, p, sim.state().bonds);
  compute_contact_forces(c, p, {c.first_moving, c.size()}, 0);
  int pushed = 0;
  for (std::size_t a = 0; a < c.size(); ++a) {
    const std::size_t i = c.candidates[a];
    if (c.force_y[a] == 0.0) continue;
    ++pushed;
    // The lower half is pushed down, the folded half up.
    if (p.x0[i] <= 0.015) {
      EXPECT_LT(c.force_y[a], 0.0) << i;
    } else {
      EXPECT_GT(c.force_y[a], 0.0) << i;
    }
  }
  EXPECT_GE(pushed, 2 * 14);  // the facing rows, all along the fold but its hinge
  const ClosestContact closest = closest_contact(c, p, sim.state().bonds, 0.003);
  ASSERT_TRUE(closest.found);
  EXPECT_EQ(p.body[closest.i], p.body[closest.j]);
  EXPECT_NEAR(closest.distance, 0.8e-3, 1e-9);
}

TEST(Contact, CandidatesAreTheOuterTwoRowsOfEachBody) {
  Simulation sim(load_case_text(drop_toml("2e-7"), "drop.toml"));
  const ContactState& c = sim.state().contact;
  // Block 8 x 8: all but the inner 4 x 4. Floor 20 x 3: every particle.
  EXPECT_EQ(c.size(), (64u - 16u) + 60u);
  EXPECT_EQ(c.first_moving, 0u + 60u);  // walls are stored first
  const ParticleStore& p = sim.particles();
  for (std::size_t a = 0; a < c.size(); ++a) {
    const std::size_t i = c.candidates[a];
    if (p.kind[i] != Kind::elastic) continue;
    const double cx = p.x0[i] - 0.010, cy = p.y0[i] - 0.010;
    EXPECT_TRUE(std::max(std::abs(cx), std::abs(cy)) > 0.002) << "an inner particle: " << i;
  }
}

TEST(Contact, ForcesDoNotDependOnWhenTheListWasBuilt) {
  Simulation sim(load_case_text(blocks_toml(0.002), "blocks.toml"));
  sim.advance(1800);  // in contact
  ContactState& c = sim.state_to_change().contact;
  const ParticleStore& p = sim.particles();
  // The Simulation's own list (threads stepping as ranks keep theirs).
  refresh_contact_list(c, p, sim.state().bonds);
  compute_contact_forces(c, p, {c.first_moving, c.size()}, 1);
  ASSERT_NE(c.stale.step.load(), 1) << "the list must be valid here";
  const std::vector<double> fx = c.force_x, fy = c.force_y;
  EXPECT_GT(std::count_if(fx.begin(), fx.end(), [](double f) { return f != 0; }), 4);
  ContactState fresh = c;
  fresh.parameters.skin *= 4;  // another list: more far pairs
  build_contact_list(fresh, p, sim.state().bonds);
  EXPECT_GT(fresh.partner.size(), c.partner.size());
  std::fill(fresh.force_x.begin(), fresh.force_x.end(), std::nan(""));
  std::fill(fresh.force_y.begin(), fresh.force_y.end(), std::nan(""));
  compute_contact_forces(fresh, p, {fresh.first_moving, fresh.size()}, 2);
  ASSERT_NE(fresh.stale.step.load(), 2) << "a fresh list cannot be stale";
  for (std::size_t a = c.first_moving; a < c.size(); ++a)
    EXPECT_TRUE(same_bits(fx[a], fresh.force_x[a]) && same_bits(fy[a], fresh.force_y[a]));
}

TEST(Contact, HeadOnBlocksReboundConservingMomentumAndNeverPassThrough) {
  Simulation sim(load_case_text(blocks_toml(), "blocks.toml"));
  const double mass = 64 * 1010.0 * 1e-6;
  const double p0 = mass * 10.0;  // each block's momentum
  double closest = 1;
  for (int k = 0; k < 50; ++k) {
    sim.advance(200);
    const Diagnostics d = sim.diagnostics();
    closest = std::min(closest, d.contact_min_distance);
    EXPECT_LT(std::abs(d.momentum_x), 1e-12 * p0);
    EXPECT_LT(std::abs(d.momentum_y), 1e-12 * p0);
    // Never through: the left block stays left of the right one.
    const ParticleStore& p = sim.particles();
    const Range l = sim.state().body_ranges[0], r = sim.state().body_ranges[1];
    EXPECT_LT(*std::max_element(p.x.begin() + l.begin, p.x.begin() + l.end),
              *std::min_element(p.x.begin() + r.begin, p.x.begin() + r.end));
  }
  EXPECT_LT(closest, 1e-3);  // they did touch
  EXPECT_GT(closest, 0.5e-3);
  EXPECT_LT(body_velocity(sim, 0)[0], -5.0);  // rebounded
  EXPECT_GT(body_velocity(sim, 1)[0], 5.0);
  EXPECT_GT(sim.state().contact.rebuilds, 1);
}

// The largest |KE + PE + contact energy - E0| / E0 over a run of `steps`.
double energy_error(const std::string& toml, std::int64_t steps, int samples) {
  Simulation sim(load_case_text(toml, "case.toml"));
  const double e0 = total_energy(sim.diagnostics());
  double worst = 0;
  for (int k = 0; k < samples; ++k) {
    sim.advance(steps / samples);
    worst = std::max(worst, std::abs(total_energy(sim.diagnostics()) - e0) / e0);
  }
  return worst;
}

TEST(Contact, EnergyErrorHalvesWithTheStep) {
  const double coarse = energy_error(blocks_toml(0.003, 0.0, "4e-7"), 5000, 50);
  const double fine = energy_error(blocks_toml(0.003, 0.0, "2e-7"), 10000, 50);
  EXPECT_LT(coarse, 0.02);
  EXPECT_GT(coarse / fine, 1.6) << coarse << " " << fine;
  EXPECT_LT(coarse / fine, 2.6) << coarse << " " << fine;
}

// An elastic block against a free rigid one, and two rigid ones: contact
// with and between rigid bodies (whose particles are placed by the body's
// projection) conserves momentum and angular momentum, and they rebound.
TEST(Contact, RigidBodiesCollideWithElasticAndRigidBodies) {
  for (const char* left_kind : {"elastic", "rigid"}) {
    SCOPED_TRACE(left_kind);
    std::string toml = blocks_toml(0.003, 200.0);
    const std::string from = "[bodies.right]\nkind = \"elastic\"";
    toml.replace(toml.find(from), from.size(), "[bodies.right]\nkind = \"rigid\"");
    if (std::string(left_kind) == "rigid") {
      const std::string left = "[bodies.left]\nkind = \"elastic\"";
      toml.replace(toml.find(left), left.size(), "[bodies.left]\nkind = \"rigid\"");
    }
    Simulation sim(load_case_text(toml, "rigid.toml"));
    const Diagnostics start = sim.diagnostics();
    // The rigid projection rounds each step, and a free rigid block drifts
    // by itself, contact or not (2.6e-12 of its momentum per 2,000 steps):
    // 5e-11 of a block's momentum (0.65 kg m/s), and 1e-10 of its moment
    // about the origin (p0 times 2 cm), over 10,000 steps.
    const double p0 = 64 * 1010.0 * 1e-6 * 10.0;
    double contact_energy = 0;
    for (int k = 0; k < 50; ++k) {
      sim.advance(200);
      const Diagnostics d = sim.diagnostics();
      contact_energy = std::max(contact_energy, d.contact_energy);
      EXPECT_NEAR(d.momentum_x, start.momentum_x, 5e-11 * p0);
      EXPECT_NEAR(d.momentum_y, start.momentum_y, 5e-11 * p0);
      EXPECT_NEAR(d.angular_momentum, start.angular_momentum, 1e-10 * p0 * 0.02);
    }
    EXPECT_GT(contact_energy, 0.0);
    EXPECT_LT(body_velocity(sim, 0)[0], 0.0);  // rebounded
    EXPECT_GT(body_velocity(sim, 1)[0], 0.0);
  }
}

TEST(Contact, ObliqueSpinningHitConservesAngularMomentum) {
  Simulation sim(load_case_text(blocks_toml(0.005, 300.0), "blocks.toml"));
  const Diagnostics start = sim.diagnostics();
  double contact_energy = 0;
  for (int k = 0; k < 50; ++k) {
    sim.advance(200);
    const Diagnostics d = sim.diagnostics();
    contact_energy = std::max(contact_energy, d.contact_energy);
    EXPECT_NEAR(d.angular_momentum, start.angular_momentum,
                1e-12 * std::abs(start.angular_momentum));
    EXPECT_NEAR(d.momentum_x, start.momentum_x, 1e-15);
    EXPECT_NEAR(d.momentum_y, start.momentum_y, 1e-15);
  }
  EXPECT_GT(contact_energy, 0.0);
}

TEST(Contact, BlockDroppedOnAWallComesBack) {
  Simulation sim(load_case_text(drop_toml("2e-7"), "drop.toml"));
  const double e0 = total_energy(sim.diagnostics());
  const double v0 = body_velocity(sim, 0)[1];
  sim.advance(10000);
  const Diagnostics d = sim.diagnostics();
  const double v1 = body_velocity(sim, 0)[1];
  EXPECT_EQ(d.contact_energy, 0.0);  // off the floor again
  // Going up; a quarter of the speed stays in the block's vibrations.
  EXPECT_GT(v1, 0.7 * -v0);
  EXPECT_NEAR(total_energy(d), e0, 0.01 * e0);
  const Range block = sim.state().body_ranges[0];
  const ParticleStore& p = sim.particles();
  EXPECT_GT(*std::min_element(p.y.begin() + block.begin, p.y.begin() + block.end), 0.003);
}

// Runs the spinning oblique hit with a thin skin (many rebuilds) at
// `threads`, stopping after `first` steps to resume a fresh simulation from
// the captured state when `resume`.
struct Outcome {
  ParticleStore particles;
  Diagnostics diagnostics;
  std::int64_t rebuilds = 0;
  double contact_energy_at_stop = 0;
};
Outcome run_blocks(int threads, bool resume) {
  set_thread_count(threads);
  const CaseSpec spec = load_case_text(blocks_toml(0.004, 500.0, "2e-7", "skin = 0.05"), "b.toml");
  Simulation sim(spec);
  sim.advance(1600);  // mid-collision
  Outcome out;
  // (Diagnostics change no bit: the forces do not depend on the list.)
  out.contact_energy_at_stop = sim.diagnostics().contact_energy;
  Simulation* last = &sim;
  Simulation resumed(spec);
  if (resume) {
    Checkpoint c = capture_state(sim.state());
    c.bond_hash = sim.state().bonds.hash();
    restore_state(resumed.state_to_change(), c, "test");
    last = &resumed;
  }
  last->advance(2400);
  out.particles = last->particles();
  out.diagnostics = last->diagnostics();
  out.rebuilds = last->state().contact.rebuilds;
  set_thread_count(available_cores());
  return out;
}

TEST(Contact, SameBitsAt1To3ThreadsAndAfterAResumeThroughManyRebuilds) {
  const Outcome one = run_blocks(1, false);
  EXPECT_GT(one.rebuilds, 30);
  EXPECT_GT(one.contact_energy_at_stop, 0.0);  // stopped mid-collision
  for (const auto& [threads, resume] : {std::pair{2, false}, {3, false}, {1, true}, {2, true}}) {
    const Outcome other = run_blocks(threads, resume);
    EXPECT_TRUE(testing::same_bits(one.particles, other.particles))
        << threads << " threads, resumed: " << resume;
    EXPECT_TRUE(same_bits(one.diagnostics.contact_energy, other.diagnostics.contact_energy));
    EXPECT_TRUE(same_bits(one.diagnostics.strain_energy, other.diagnostics.strain_energy));
  }
}

TEST(Contact, InterpenetrationStopsTheRunNamingThePair) {
  // Far too soft a contact: the blocks sink into each other.
  Simulation sim(load_case_text(blocks_toml(0.0, 0.0, "2e-7", "stiffness = 1.0e3"), "b.toml"));
  StabilityVerdict v;
  for (int k = 0; k < 100 && v.ok; ++k) {
    sim.advance(100);
    v = sim.check_stability();
  }
  ASSERT_FALSE(v.ok);
  EXPECT_NE(v.criterion.find("interpenetration"), std::string::npos) << v.criterion;
  EXPECT_TRUE(v.has_neighbor);
  EXPECT_NE(sim.particles().body[v.particle], sim.particles().body[v.neighbor]);
  EXPECT_LT(v.value, v.limit);
}

// The check runs every few hundred steps, a dip below min_distance may last
// fewer: the contact pass marks the first step of one, and the next check
// reports it, even when the pair has parted again by then.
TEST(Contact, ADipBetweenChecksIsReported) {
  Simulation sim(load_case_text(blocks_toml(0.0, 0.0, "2e-7", "stiffness = 2.0e6"), "b.toml"));
  double sampled = 1;  // the closest distance seen every 100 steps
  for (int k = 0; k < 100; ++k) {
    sim.advance(100);
    sampled = std::min(sampled, sim.diagnostics().contact_min_distance);
  }
  EXPECT_GT(sampled, 0.5e-3);  // never seen below the limit at a sample
  const StabilityVerdict v = sim.check_stability();
  ASSERT_FALSE(v.ok);
  EXPECT_NE(v.criterion.find("came closer than 0.5 of the contact distance"), std::string::npos)
      << v.criterion;
  EXPECT_NE(v.criterion.find("at step 1"), std::string::npos) << v.criterion;
  EXPECT_TRUE(v.has_neighbor);
  // Without the dip (the default stiffness) nothing is reported.
  Simulation stiff(load_case_text(blocks_toml(), "b.toml"));
  stiff.advance(10000);
  EXPECT_TRUE(stiff.check_stability().ok);
}

TEST(Contact, AutomaticStepAccountsForTheContactStiffness) {
  const std::string toml = blocks_toml(0.0, 0.0, "\"auto\"");
  const auto dt = [&](const std::vector<std::string>& overrides) {
    return Simulation(load_case_text(toml, "b.toml", overrides)).spec().dt;
  };
  const double with = dt({}), without = dt({"contact.enabled=false"});
  EXPECT_LT(with, without);
  EXPECT_GT(with, 0.3 * without);
  EXPECT_LT(dt({"contact.stiffness=1e10"}), 0.5 * with);
}

TEST(Contact, ACaseWithoutContactHasNoCandidates) {
  Simulation sim(testing::rod_case());
  EXPECT_FALSE(sim.state().contact.enabled());
  EXPECT_EQ(sim.diagnostics().contact_energy, 0.0);
}

}  // namespace
}  // namespace mpsolid
