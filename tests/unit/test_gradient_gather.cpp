// The corrected-gradient models as per-particle gathers in any dimension
// (kernels/gradient_gather_model.hpp): in 3D the oracle's numbers
// (kernels/reference/corrected_gradient_nd.hpp), in 2D the plane slot
// kernels' numbers; in space the forces are minus the energy's gradient, a
// rigid turn is stress-free, momentum and angular momentum are kept, and the
// step (src/solver/step.hpp) conserves energy with the same bits at 1 and 2
// threads; every path of the gathers (kLanes particles at a time, row by
// row) gives the same bits.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kernels/finite_strain_model.hpp"
#include "kernels/gradient_gather_model.hpp"
#include "kernels/linear_elastic_model.hpp"
#include "kernels/reference/corrected_gradient_nd.hpp"
#include "neighbor/bond_search.hpp"
#include "src/solver/step.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using NeoHookean3 = GradientGatherModel<3, NeoHookeanLaw>;
using Hooke3 = GradientGatherModel<3, HookeLaw>;

constexpr double kL0 = 1e-3;
constexpr double kLambda = 2.8e7, kMu = 9.4e5, kDensity = 1100.0;  // rubber

OptionValues hourglass(bool consistent) {
  OptionValues options = default_options(hourglass_option_table());
  options.choices["hourglass_form"] = consistent ? "consistent" : "frozen";
  return options;
}

// An n^3 rubber block, stretched by f and jiggled: a deformed 3D state.
SolverState deformed_block(int n, const Matrix3d& f, unsigned seed) {
  SolverState s;
  s.particles = testing::space_block(n, n, n, kL0, kLambda, kMu, kDensity);
  s.bonds = build_bonds(s.particles, bond_geometry_3d(kL0));
  ParticleStore& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector3d x = f * Vector3d(p.x0[i], p.y0[i], p.z0[i]);
    p.x[i] = x[0];
    p.y[i] = x[1];
    p.z[i] = x[2];
  }
  if (seed != 0) testing::jiggle(p, kL0, seed, 0.0);
  return s;
}

Matrix3d stretch() {
  Matrix3d f;
  f << 1.05, 0.02, 0.0, 0.01, 0.97, 0.03, -0.02, 0.01, 1.02;
  return f;
}

reference::GradientState<3> oracle_state(const SolverState& s) {
  const ParticleStore& p = s.particles;
  reference::GradientState<3> o;
  const auto n = static_cast<Eigen::Index>(p.size());
  o.x.resize(3, n);
  o.x0.resize(3, n);
  o.bonds.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    o.x.col(static_cast<Eigen::Index>(i)) << p.x[i], p.y[i], p.z[i];
    o.x0.col(static_cast<Eigen::Index>(i)) << p.x0[i], p.y0[i], p.z0[i];
    o.lambda.push_back(p.lambda[i]);
    o.mu.push_back(p.mu[i]);
    for (std::uint32_t b = s.bonds.begin(i); b < s.bonds.end(i); ++b)
      o.bonds[i].push_back(s.bonds.neighbor[b]);
  }
  o.re = s.bonds.geometry.re;
  o.n0 = number_density(s.bonds);
  o.volume = s.bonds.geometry.volume;
  return o;
}

template <class Model>
double strain_energy(const Model& model, const ParticleStore& p, const BondTable& bonds) {
  double e = 0;
  for (std::size_t i = 0; i < p.size(); ++i) e += model.particle_strain_energy(p, bonds, i);
  return e;
}

// kLanes particles at a time along the row patterns (whole and masked
// rows), kLanes consecutive particles over their own rows, and row by row:
// the same bits for F, J, the stresses and forces, with either hourglass
// form, on a deformed block whose first layers are off the lattice.
TEST(GradientGather, EveryPathGivesTheRowByRowBits) {
  for (const bool consistent : {false, true}) {
    SolverState lanes = deformed_block(12, stretch(), 6);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1e-4 * kL0, 1e-4 * kL0);
    for (std::size_t i = 0; i < 2 * 12 * 12; ++i) lanes.particles.z0[i] += u(rng);
    lanes.bonds = build_bonds(lanes.particles, bond_geometry_3d(kL0));
    SolverState rows = lanes;
    NeoHookean3 by_lanes(lanes.particles, lanes.bonds, hourglass(consistent));
    NeoHookean3 by_rows(rows.particles, rows.bonds, hourglass(consistent));
    by_rows.take_rows_one_by_one();
    for (auto [model, s] : {std::pair{&by_lanes, &lanes}, std::pair{&by_rows, &rows}}) {
      model->compute_strain(s->particles, s->bonds, s->particles.all());
      model->compute_forces(s->particles, s->bonds, s->particles.all());
    }
    EXPECT_TRUE(testing::same_bits(lanes.particles, rows.particles)) << consistent;
    for (std::size_t i = 0; i < lanes.particles.size(); ++i)
      ASSERT_EQ(by_lanes.deformation_gradient(i), by_rows.deformation_gradient(i)) << i;
    EXPECT_GT(testing::max_abs(lanes.particles.fz), 0.0);
  }
}

// Moves every reference position off the lattice by up to 1e-3 l0 (seeded)
// and rebuilds the bonds: hundreds of distinct bond lengths.
void off_lattice(SolverState& s) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1e-3 * kL0, 1e-3 * kL0);
  ParticleStore& p = s.particles;
  for (auto* v : {&p.x0, &p.y0, &p.z0})
    for (double& c : *v) c += u(rng);
  s.bonds = build_bonds(p, bond_geometry_3d(kL0));
}

// One byte per bond entry names its length's shell: four in the cubic
// lattice (l0 times 1, sqrt 2, sqrt 3, 2), three in the square one, none
// for a table off the lattice.
TEST(GradientGather, BondShells) {
  SolverState s = deformed_block(5, stretch(), 0);
  const BondShells cubic = find_bond_shells(s.particles, s.bonds);
  ASSERT_EQ(cubic.length.size(), 4u);
  ASSERT_EQ(cubic.of_entry.size(), s.bonds.entry_count());
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    for (std::uint32_t b = s.bonds.begin(i); b < s.bonds.end(i); ++b) {
      ASSERT_NE(cubic.of_entry[b], BondShells::kOff);
      ASSERT_NEAR(cubic.length[cubic.of_entry[b]],
                  std::sqrt(reference_length2(s.particles, i, s.bonds.neighbor[b])), 1e-15);
    }
  Simulation sim(testing::rod_case());
  EXPECT_EQ(find_bond_shells(sim.particles(), sim.state().bonds).length.size(), 3u);
  off_lattice(s);
  const BondShells off = find_bond_shells(s.particles, s.bonds);
  EXPECT_TRUE(off.length.empty());
  for (const std::uint8_t shell : off.of_entry) ASSERT_EQ(shell, BondShells::kOff);
}

// With shells (the lattice) and without (off it), the oracle's numbers.
TEST(GradientGather, In3DItGivesTheOraclesNumbers) {
  for (const bool consistent : {true, false})
    for (const bool lattice : {true, false}) {
      SolverState s = deformed_block(6, stretch(), 11);
      if (!lattice) off_lattice(s);
      ParticleStore& p = s.particles;
      NeoHookean3 model(p, s.bonds, hourglass(consistent));
      model.compute_strain(p, s.bonds, p.all());
      model.compute_forces(p, s.bonds, p.all());
      const reference::GradientResultNd<3> o =
          reference::finite_strain_nd<3>(oracle_state(s), 1.0, consistent);
      const double scale = testing::max_abs(o.force);
      ASSERT_GT(scale, 0.0);
      for (std::size_t i = 0; i < p.size(); ++i) {
        const auto c = static_cast<Eigen::Index>(i);
        ASSERT_LT((model.deformation_gradient(i) - o.def_grad[i]).cwiseAbs().maxCoeff(), 1e-13)
            << i;
        ASSERT_NEAR(p.fx[i], o.force(0, c), 1e-12 * scale) << i << " consistent " << consistent;
        ASSERT_NEAR(p.fy[i], o.force(1, c), 1e-12 * scale) << i;
        ASSERT_NEAR(p.fz[i], o.force(2, c), 1e-12 * scale) << i;
        ASSERT_NEAR(p.strain[i], std::log(o.def_grad[i].determinant()), 1e-13) << i;
      }
      EXPECT_NEAR(strain_energy(model, p, s.bonds), o.energy, 1e-12 * o.energy);
    }
}

// The 2D instantiation computes the plane slot kernels' forces, strain,
// pressure and energy to round-off: one text for the plane and space.
template <class Slot, class Gather>
void expect_the_slot_kernels_numbers(const char* model_name) {
  Simulation sim(testing::rod_case({std::string("model=") + model_name}));
  ParticleStore p = sim.particles();
  const BondTable& bonds = sim.state().bonds;
  testing::jiggle(p, sim.spec().l0, 5, 0.0);
  const OptionValues options = default_options(Slot::options());
  Slot slot(p, bonds, options);
  slot.compute_strain(p, bonds, p.all());
  slot.compute_forces(p, bonds, p.moving());
  const ParticleStore by_slots = p;
  const double slot_energy = strain_energy(slot, p, bonds);
  Gather gather(p, bonds, options);
  gather.compute_strain(p, bonds, p.all());
  gather.compute_forces(p, bonds, p.moving());
  const double scale = std::max(testing::max_abs(by_slots.fx), testing::max_abs(by_slots.fy));
  const double stress = testing::max_abs(by_slots.pressure);
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = p.moving().begin; i < p.moving().end; ++i) {
    ASSERT_NEAR(p.fx[i], by_slots.fx[i], 1e-12 * scale) << model_name << " " << i;
    ASSERT_NEAR(p.fy[i], by_slots.fy[i], 1e-12 * scale) << model_name << " " << i;
    ASSERT_NEAR(p.strain[i], by_slots.strain[i], 1e-13) << model_name << " " << i;
    ASSERT_NEAR(p.pressure[i], by_slots.pressure[i], 1e-12 * stress) << model_name << " " << i;
  }
  EXPECT_NEAR(strain_energy(gather, p, bonds), slot_energy, 1e-12 * slot_energy) << model_name;
}

TEST(GradientGather, In2DItGivesThePlaneSlotKernelsNumbers) {
  expect_the_slot_kernels_numbers<FiniteStrainModel, GradientGatherModel<2, NeoHookeanLaw>>(
      "finite_strain");
  expect_the_slot_kernels_numbers<LinearElasticModel, GradientGatherModel<2, HookeLaw>>(
      "linear_elastic");
}

// f_i = -dE/dx_i by central differences, for both laws, hourglass included.
template <class Model>
void expect_forces_are_minus_the_energy_gradient() {
  SolverState s = deformed_block(4, stretch(), 3);
  ParticleStore& p = s.particles;
  Model model(p, s.bonds, hourglass(true));
  const auto energy = [&] {
    model.compute_strain(p, s.bonds, p.all());
    return strain_energy(model, p, s.bonds);
  };
  energy();
  model.compute_forces(p, s.bonds, p.all());
  const ParticleStore at = p;
  const double scale =
      std::max({testing::max_abs(at.fx), testing::max_abs(at.fy), testing::max_abs(at.fz)});
  const double h = 1e-7 * kL0;
  for (const std::size_t i : {std::size_t{0}, std::size_t{21}, std::size_t{42}, p.size() - 1})
    for (std::vector<double>* axis : {&p.x, &p.y, &p.z}) {
      const double keep = (*axis)[i];
      (*axis)[i] = keep + h;
      const double up = energy();
      (*axis)[i] = keep - h;
      const double down = energy();
      (*axis)[i] = keep;
      const double force = axis == &p.x ? at.fx[i] : axis == &p.y ? at.fy[i] : at.fz[i];
      EXPECT_NEAR(force, -(up - down) / (2 * h), 1e-6 * scale) << Model::name << " " << i;
    }
}

TEST(GradientGather, InSpaceTheForcesAreMinusTheEnergysGradient) {
  expect_forces_are_minus_the_energy_gradient<NeoHookean3>();
  expect_forces_are_minus_the_energy_gradient<Hooke3>();
}

// A rigid turn about a skew axis: F is the rotation at every particle and
// the finite_strain forces vanish; the linear law's do not (it is not
// rotation invariant).
TEST(GradientGather, ARigidTurnInSpaceIsStressFreeForFiniteStrain) {
  const Matrix3d turn = Eigen::AngleAxisd(0.7, Vector3d(1, -2, 0.5).normalized()).matrix();
  SolverState s = deformed_block(5, turn, 0);
  ParticleStore& p = s.particles;
  NeoHookean3 model(p, s.bonds, hourglass(true));
  model.compute_strain(p, s.bonds, p.all());
  model.compute_forces(p, s.bonds, p.all());
  // The force scale of a 1 % stretch.
  SolverState stretched = deformed_block(5, 1.01 * Matrix3d::Identity(), 0);
  NeoHookean3 reference(stretched.particles, stretched.bonds, hourglass(true));
  reference.compute_strain(stretched.particles, stretched.bonds, stretched.particles.all());
  reference.compute_forces(stretched.particles, stretched.bonds, stretched.particles.all());
  const double scale = testing::max_abs(stretched.particles.fx);
  for (std::size_t i = 0; i < p.size(); ++i) {
    EXPECT_LT((model.deformation_gradient(i) - turn).cwiseAbs().maxCoeff(), 1e-12) << i;
    EXPECT_LT(std::abs(p.fx[i]) + std::abs(p.fy[i]) + std::abs(p.fz[i]), 1e-9 * scale) << i;
  }
  Hooke3 linear(p, s.bonds, hourglass(true));
  linear.compute_strain(p, s.bonds, p.all());
  linear.compute_forces(p, s.bonds, p.all());
  EXPECT_GT(testing::max_abs(p.fx), 0.1 * scale);
}

// Each bond's two terms are exact negatives: the forces sum to zero, and
// (the law rotation invariant) their moments too, to round-off.
TEST(GradientGather, MomentumAndAngularMomentumAreKept) {
  SolverState s = deformed_block(6, stretch(), 17);
  ParticleStore& p = s.particles;
  NeoHookean3 model(p, s.bonds, hourglass(true));
  model.compute_strain(p, s.bonds, p.all());
  model.compute_forces(p, s.bonds, p.all());
  Vector3d sum = Vector3d::Zero(), moment = Vector3d::Zero();
  double scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector3d f(p.fx[i], p.fy[i], p.fz[i]);
    sum += f;
    moment += Vector3d(p.x[i], p.y[i], p.z[i]).cross(f);
    scale = std::max(scale, f.norm());
  }
  EXPECT_LT(sum.norm(), 1e-12 * scale * static_cast<double>(p.size()));
  EXPECT_LT(moment.norm(), 1e-12 * scale * 6 * kL0 * static_cast<double>(p.size()));
}

// The step (strain pass, forces, integration) on a free, jiggled 3D block
// for 100 l0 / c: kinetic plus strain energy kept, its error falling
// faster than dt, momentum kept, and the same bits at 1 and 2 threads.
struct SteppedBlock {
  ParticleStore particles;
  double energy_error;  // relative to the initial strain energy
};
SteppedBlock step_block(int threads, double courant) {
  set_thread_count(threads);
  SolverState s = deformed_block(6, Matrix3d::Identity(), 23);
  NeoHookean3 model(s.particles, s.bonds, hourglass(true));
  PhaseTimers timers;
  const double wave_speed = std::sqrt((kLambda + 2 * kMu) / kDensity);
  const double dt = courant * kL0 / wave_speed;
  const auto energy = [&] {
    update_strain(model, s, timers);
    const ParticleStore& p = s.particles;
    double kinetic = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      kinetic += 0.5 / p.inv_mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    return kinetic + strain_energy(model, p, s.bonds);
  };
  const double start = energy();
  advance_steps(model, s, dt, timers, std::llround(100.0 / courant));
  const double end = energy();
  set_thread_count(available_cores());
  return {s.particles, std::abs(end - start) / start};
}

TEST(GradientGather, TheStepInSpaceKeepsEnergyWithTheSameBitsAt1And2Threads) {
  const SteppedBlock coarse = step_block(1, 0.1), one = step_block(1, 0.05),
                     two = step_block(2, 0.05);
  EXPECT_TRUE(testing::same_bits(one.particles, two.particles));
  EXPECT_LT(coarse.energy_error, 1.5e-2);
  EXPECT_LT(one.energy_error, 0.45 * coarse.energy_error);
  const ParticleStore& p = one.particles;
  Vector3d momentum = Vector3d::Zero();
  double scale = 0, kinetic = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector3d v(p.vx[i], p.vy[i], p.vz[i]);
    momentum += v / p.inv_mass[i];
    scale += v.norm() / p.inv_mass[i];
    kinetic += v.squaredNorm();
  }
  EXPECT_GT(kinetic, 0.0);  // it moved
  EXPECT_LT(momentum.norm(), 1e-12 * scale);
}

}  // namespace
}  // namespace mpsolid
