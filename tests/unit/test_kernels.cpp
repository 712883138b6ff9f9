// The fast gather kernels against the plain pair-loop reference (paper's
// Eq. 3-7 in acceleration form) on a randomly deformed, rotated rod.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "kernels/paper_model.hpp"
#include "kernels/reference/bond_loop.hpp"
#include "kernels/reference/reference_kernels.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(PaperModel, KernelsMatchThePlainReference) {
  Simulation sim(testing::rod_case());
  ParticleStore& p = sim.state_to_change().particles;
  testing::jiggle(p, sim.spec().l0, 3, 0.4);  // a large common rotation plus noise
  sim.refresh_fields();
  testing::run_model_passes<PaperModel>(p, sim.state().bonds);
  const reference::PaperResult ref = reference::paper_model(p, sim.state().bonds);

  auto compare = [&](const std::vector<double>& fast, const std::vector<double>& slow,
                     std::size_t begin, const char* what) {
    const double scale = testing::max_abs(slow);
    ASSERT_GT(scale, 0.0) << what;
    for (std::size_t i = begin; i < p.size(); ++i)
      ASSERT_NEAR(fast[i], slow[i], 1e-11 * scale) << what << " of particle " << i;
  };
  compare(p.strain, ref.strain, 0, "strain");
  compare(p.pressure, ref.pressure, 0, "pressure");
  compare(p.fx, ref.fx, p.moving().begin, "fx");
  compare(p.fy, ref.fy, p.moving().begin, "fy");
  compare(p.torque, ref.torque, p.moving().begin, "torque");
}

// Each end computing its own bonds in CSR order (for_each_bond), the way the
// kernels did before bonds were computed once: the slot kernels must give
// these bits exactly, on the pattern path and the per-entry path alike.
struct PassResult {
  std::vector<double> strain, pressure, fx, fy, torque;
};

template <bool EnergyConsistent>
PassResult per_entry_passes(const ParticleStore& p, const BondTable& bonds) {
  const auto coefficients = PaperModelT<EnergyConsistent>::entry_coefficients(p, bonds);
  const auto& sc = coefficients.strain;
  const auto& kc = coefficients.spring;
  const double volume = bonds.geometry.volume;
  PassResult r;
  for (auto* v : {&r.strain, &r.pressure, &r.fx, &r.fy, &r.torque}) v->assign(p.size(), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    double eps = 0.0;
    for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double inv_len) {
      eps += sc[b] * bond_math::normal_extension(v, inv_len);
    });
    r.strain[i] = eps;
    r.pressure[i] = -p.lambda[i] * eps;
  }
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    double fx = 0.0, fy = 0.0, torque = 0.0;
    for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t j, const auto& v, double inv_len) {
      const double c = volume * sc[b] * (r.pressure[i] + r.pressure[j]) * inv_len;
      fx += kc[b] * v.ux - c * v.rx;
      fy += kc[b] * v.uy - c * v.ry;
      double bond_torque = kc[b] * bond_math::cross(v.rx, v.ry, v.ux, v.uy);
      if constexpr (EnergyConsistent) {
        const double un = bond_math::normal_extension(v, inv_len) * inv_len;
        fx -= c * (v.ux - un * v.rx);
        fy -= c * (v.uy - un * v.ry);
        bond_torque += c * bond_math::cross(v.ux, v.uy, v.rx, v.ry);
      }
      torque += bond_torque;
    });
    r.fx[i] = fx;
    r.fy[i] = fy;
    r.torque[i] = 0.5 * torque;
  }
  return r;
}

template <bool EnergyConsistent>
void expect_slot_kernels_give_per_entry_bits(const CaseSpec& spec, bool prefetching = false) {
  Simulation sim(spec);
  ParticleStore& p = sim.state_to_change().particles;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    p.x[i] += 0.05 * spec.l0 * n(rng);
    p.y[i] += 0.05 * spec.l0 * n(rng);
    p.theta[i] = 0.3 * n(rng);
  }
  sim.refresh_fields();
  const BondTable& bonds = sim.state().bonds;
  PaperModelT<EnergyConsistent> model(p, bonds, {});
  ASSERT_EQ(model.prefetches(), prefetching);  // both instances of the force gather are tested
  model.compute_strain(p, bonds, p.all());
  model.compute_forces(p, bonds, p.moving());
  const PassResult r = per_entry_passes<EnergyConsistent>(p, bonds);
  for (std::size_t i = 0; i < p.size(); ++i) {
    ASSERT_EQ(p.strain[i], r.strain[i]) << "particle " << i;
    ASSERT_EQ(p.pressure[i], r.pressure[i]) << "particle " << i;
    if (i < p.moving().begin) continue;
    ASSERT_EQ(p.fx[i], r.fx[i]) << "particle " << i;
    ASSERT_EQ(p.fy[i], r.fy[i]) << "particle " << i;
    ASSERT_EQ(p.torque[i], r.torque[i]) << "particle " << i;
  }
}

TEST(PaperModel, SlotKernelsGiveTheBitsOfThePerEntryGather) {
  for (int threads : {1, 2, 3}) {
    set_thread_count(threads);
    expect_slot_kernels_give_per_entry_bits<false>(testing::rod_case());
    expect_slot_kernels_give_per_entry_bits<false>(testing::rod_case({"l0=0.001"}));
    expect_slot_kernels_give_per_entry_bits<false>(testing::free_block_case(12, 7, true));
  }
  set_thread_count(1);
}

TEST(PaperConservative, SlotKernelsGiveTheBitsOfThePerEntryGather) {
  expect_slot_kernels_give_per_entry_bits<true>(testing::rod_case());
  expect_slot_kernels_give_per_entry_bits<true>(testing::free_block_case(12, 7, true));
}

// At 0.25 mm the slot data exceed kPrefetchAboveBytes: the prefetching
// instance of the force gather.
TEST(PaperModel, PrefetchingGatherGivesTheBitsOfThePerEntryGather) {
  set_thread_count(2);
  expect_slot_kernels_give_per_entry_bits<false>(testing::rod_case({"l0=0.00025"}), true);
  expect_slot_kernels_give_per_entry_bits<true>(testing::rod_case({"l0=0.00025"}), true);
  set_thread_count(1);
}

}  // namespace
}  // namespace mpsolid
