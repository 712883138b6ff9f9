// The row patterns the space gathers take kLanes particles at a time with
// (kernels/row_patterns.hpp): every particle of a run has its own row, in
// order, as the entries its mask names; the pattern's offsets stay inside
// the table; a block's lines are almost all on runs; and bonds off the
// lattice's shells leave their rows to the row by row path.
#include <gtest/gtest.h>

#include <random>

#include "kernels/bond_shells.hpp"
#include "kernels/row_patterns.hpp"
#include "neighbor/bond_search.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

constexpr double kL0 = 1e-3;

struct Lattice {
  ParticleStore p;
  BondTable bonds;
  BondShells shells;
};

Lattice block(int nx, int ny, int nz) {
  Lattice l;
  l.p = testing::space_block(nx, ny, nz, kL0, 1e9, 1e9, 1000.0);
  l.bonds = build_bonds(l.p, bond_geometry_3d(kL0));
  l.shells = find_bond_shells(l.p, l.bonds);
  return l;
}

// Checks every run's rows against the table; counts the particles on runs.
void expect_runs_match_the_table(const Lattice& l, const RowPatterns& rows, std::size_t& on_runs) {
  on_runs = 0;
  ASSERT_FALSE(rows.runs.empty());
  EXPECT_EQ(rows.runs.front().begin, 0u);
  EXPECT_EQ(rows.runs.back().end, l.p.size());
  for (std::size_t r = 0; r < rows.runs.size(); ++r) {
    const RowPatterns::Run& run = rows.runs[r];
    if (r > 0) {
      EXPECT_EQ(run.begin, rows.runs[r - 1].end);
    }
    if (run.pattern < 0) continue;
    const RowPattern& pattern = rows.patterns[static_cast<std::size_t>(run.pattern)];
    for (std::size_t i = run.begin; i < run.end; ++i) {
      ++on_runs;
      std::vector<std::size_t> partners;
      for (std::size_t k = 0; k < pattern.partner_shift.size(); ++k) {
        const std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) + pattern.partner_shift[k];
        ASSERT_GE(j, 0) << i;
        ASSERT_LT(j, static_cast<std::ptrdiff_t>(l.p.size())) << i;
        if ((rows.present[i] >> k) & 1) {
          partners.push_back(static_cast<std::size_t>(j));
          const std::uint32_t b =
              l.bonds.begin(i) + static_cast<std::uint32_t>(partners.size() - 1);
          ASSERT_LT(b, l.bonds.end(i)) << i;
          EXPECT_EQ(l.shells.of_entry[b], pattern.shell[k]) << i;
        }
      }
      ASSERT_EQ(partners.size(), l.bonds.end(i) - l.bonds.begin(i)) << i;
      for (std::size_t k = 0; k < partners.size(); ++k)
        EXPECT_EQ(partners[k], l.bonds.neighbor[l.bonds.begin(i) + k]) << i;
    }
  }
}

TEST(RowPatterns, EveryRunHoldsItsParticlesOwnRowsInOrder) {
  const Lattice l = block(12, 10, 9);
  const RowPatterns rows = find_row_patterns(l.bonds, l.shells.of_entry, BondShells::kOff);
  std::size_t on_runs = 0;
  expect_runs_match_the_table(l, rows, on_runs);
  // Only rows whose pattern would reach outside the table (the first and
  // last two layers' far ends) are left row by row.
  EXPECT_GT(static_cast<double>(on_runs), 0.9 * static_cast<double>(l.p.size()));
  std::printf("%zu of %zu particles on %zu runs of %zu patterns\n", on_runs, l.p.size(),
              rows.runs.size(), rows.patterns.size());
}

TEST(RowPatterns, RowsWithBondsOffTheShellsAreTakenRowByRow) {
  Lattice l = block(12, 10, 9);
  // Particles of the first three layers off the lattice by up to 1e-4 l0.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1e-4 * kL0, 1e-4 * kL0);
  for (std::size_t i = 0; i < 3 * 12 * 10; ++i) l.p.x0[i] += u(rng);
  l.bonds = build_bonds(l.p, bond_geometry_3d(kL0));
  l.shells = find_bond_shells(l.p, l.bonds);
  const RowPatterns rows = find_row_patterns(l.bonds, l.shells.of_entry, BondShells::kOff);
  std::size_t on_runs = 0;
  expect_runs_match_the_table(l, rows, on_runs);
  std::size_t off = 0;
  for (const RowPatterns::Run& run : rows.runs) {
    for (std::size_t i = run.begin; i < run.end; ++i) {
      bool on_shells = true;
      for (std::uint32_t b = l.bonds.begin(i); b < l.bonds.end(i); ++b)
        on_shells = on_shells && l.shells.of_entry[b] != BondShells::kOff;
      if (!on_shells) {
        ++off;
        EXPECT_LT(run.pattern, 0) << i;
      }
    }
  }
  EXPECT_GT(off, 0u);
}

}  // namespace
}  // namespace mpsolid
