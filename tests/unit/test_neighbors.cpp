// Neighbour search and the bond table: n0, bond counts, and the three
// searches (cell list, k-d tree, brute force) giving identical lists.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "neighbor/bond_search.hpp"
#include "neighbor/neighbor_lists.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(NumberDensity, MatchesModelValue) {
  for (double l0 : {2e-3, 1e-3, 0.37}) {
    const BondGeometry g = bond_geometry(l0, 1.0);
    EXPECT_NEAR(bond_math::lattice_number_density(g.l0, g.re), 6.539697, 1e-6) << "l0 = " << l0;
    EXPECT_DOUBLE_EQ(g.re, 2.1 * l0);
  }
}

TEST(BondTable, InteriorParticleHasTwelveBondsSummingToN0) {
  Simulation sim(testing::rod_case());
  const ParticleStore& p = sim.particles();
  const BondTable& bonds = sim.state().bonds;
  // A rod particle far from every surface: x = 51 mm, y = 1 mm.
  std::size_t interior = p.size();
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(p.x0[i] - 0.051) < 1e-9 && std::abs(p.y0[i] - 0.001) < 1e-9) interior = i;
  ASSERT_LT(interior, p.size());
  EXPECT_EQ(bonds.end(interior) - bonds.begin(interior), 12u);
  double n = 0.0;
  for (std::uint32_t b = bonds.begin(interior); b < bonds.end(interior); ++b)
    n += bond_math::weight(std::hypot(bonds.r0x[b], bonds.r0y[b]), bonds.geometry.re);
  EXPECT_NEAR(n, 6.539697, 1e-6);
  // 1130 particles in the paper's case; every bond stored from both ends.
  EXPECT_EQ(p.size(), 1130u);
  EXPECT_EQ(bonds.entry_count() % 2, 0u);
}

TEST(BondTable, IsSymmetricAndSorted) {
  Simulation sim(testing::rod_case());
  const BondTable& bonds = sim.state().bonds;
  const auto paper = PaperModel::entry_coefficients(sim.particles(), bonds);
  for (std::size_t i = 0; i < bonds.particle_count(); ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      if (b + 1 < bonds.end(i)) {
        EXPECT_LT(bonds.neighbor[b], bonds.neighbor[b + 1]);
      }
      const std::size_t j = bonds.neighbor[b];
      bool found = false;
      for (std::uint32_t c = bonds.begin(j); c < bonds.end(j); ++c) {
        if (bonds.neighbor[c] != i) continue;
        {
          found = true;
          // r0_ji = -r0_ij and the paper model's coefficients agree, bit for bit.
          EXPECT_EQ(bonds.r0x[c], -bonds.r0x[b]);
          EXPECT_EQ(bonds.r0y[c], -bonds.r0y[b]);
          EXPECT_EQ(paper.spring[c], paper.spring[b]);
          EXPECT_EQ(paper.strain[c], paper.strain[b]);
        }
      }
      EXPECT_TRUE(found) << i << " -> " << j << " has no reverse bond";
    }
}

void expect_all_searches_agree(const PointCloud& points, double radius, std::size_t min_pairs) {
  const NeighborLists brute = find_neighbors_brute_force(points, radius);
  const NeighborLists cells = find_neighbors_cell_list(points, radius);
  const NeighborLists tree = find_neighbors_kdtree(points, radius);
  const NeighborLists sparse = find_neighbors_sparse_cells(points, radius);
  EXPECT_GE(brute.pair_count(), min_pairs);
  EXPECT_TRUE(cells == brute) << "cell list differs from brute force";
  EXPECT_TRUE(sparse == brute) << "sparse cells differ from brute force";
  EXPECT_TRUE(tree == brute) << "k-d tree differs from brute force";
}

TEST(NeighborSearch, AgreeOnLattices) {
  for (double l0 : {2e-3, 1e-3, 0.1}) {
    std::vector<double> x, y;
    for (int m = -7; m < 11; ++m)
      for (int k = -3; k < 30; ++k) {
        x.push_back((k + 0.5) * l0);
        y.push_back((m + 0.5) * l0);
      }
    expect_all_searches_agree({x, y}, 2.1 * l0, 12 * x.size() / 2);
    // A radius exactly on a shell (2 l0): borderline pairs decided by one predicate.
    expect_all_searches_agree({x, y}, 2.0 * l0, 8 * x.size() / 2);
  }
}

// Two clusters a kilometre apart at a millimetre radius: a dense grid would
// need 1e12 cells; the sparse search needs memory for the points only.
TEST(NeighborSearch, SparseCellsHandleAHugeSpread) {
  std::vector<double> x, y;
  for (int k = 0; k < 20; ++k) {
    x.push_back(k * 0.5e-3);
    y.push_back(0.0);
    x.push_back(1000.0 + k * 0.5e-3);
    y.push_back(-1000.0);
  }
  const NeighborLists sparse = find_neighbors_sparse_cells({x, y}, 1.1e-3);
  EXPECT_TRUE(sparse == find_neighbors_brute_force({x, y}, 1.1e-3));
  EXPECT_EQ(sparse.pair_count(), 2u * (2 * 19 + 2 * 18));
  const std::vector<double> bad = {0.0, std::nan("")}, zeros = {0.0, 0.0};
  EXPECT_THROW(find_neighbors_sparse_cells({bad, zeros}, 1.0), std::invalid_argument);
}

TEST(NeighborSearch, AgreeOnRandomClouds) {
  std::mt19937_64 rng(42);
  for (std::size_t n : {1u, 2u, 50u, 2000u}) {
    std::uniform_real_distribution<double> u(-1.0, 3.0);
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = u(rng);
      y[i] = 0.25 * u(rng);
    }
    expect_all_searches_agree({x, y}, 0.1, 0);
  }
  // Duplicated points and a degenerate line.
  std::vector<double> x = {0, 0, 0, 1e-3, 5}, y = {0, 0, 1e-3, 0, 0};
  expect_all_searches_agree({x, y}, 2e-3, 8);
}

TEST(NeighborSearch, AgreeInSpace) {
  // A cubic lattice, at a radius between shells and on one (2 l0).
  std::vector<double> x, y, z;
  const double l0 = 1e-3;
  for (int c = -2; c < 6; ++c)
    for (int b = 0; b < 7; ++b)
      for (int a = -3; a < 9; ++a) {
        x.push_back((a + 0.5) * l0);
        y.push_back((b + 0.5) * l0);
        z.push_back((c + 0.5) * l0);
      }
  expect_all_searches_agree({x, y, z}, 2.1 * l0, 32 * x.size() / 4);
  expect_all_searches_agree({x, y, z}, 2.0 * l0, 26 * x.size() / 4);
  // Random clouds, flat ones among them (all z equal: still searched in space).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 3.0);
  for (const double depth : {1.0, 0.1, 0.0}) {
    std::vector<double> rx(1500), ry(1500), rz(1500);
    for (std::size_t i = 0; i < rx.size(); ++i) {
      rx[i] = u(rng);
      ry[i] = 0.5 * u(rng);
      rz[i] = depth * u(rng);
    }
    expect_all_searches_agree({rx, ry, rz}, 0.2, 0);
  }
}

// A long thin cloud in space: the grid grows its cells to stay near the
// points' count instead of allocating the per-axis cap cubed.
TEST(NeighborSearch, SpaceGridStaysSmallForASpreadCloud) {
  std::vector<double> x, y, z;
  for (int k = 0; k < 40; ++k) {
    x.push_back(k * 1e3);
    y.push_back(k % 2 ? 1e3 : 0.0);
    z.push_back(k % 3 ? -1e3 : 0.0);
  }
  x.push_back(0.5e-3);
  y.push_back(0.0);
  z.push_back(0.0);
  const NeighborLists cells = find_neighbors_cell_list({x, y, z}, 1e-3);
  EXPECT_TRUE(cells == find_neighbors_brute_force({x, y, z}, 1e-3));
  EXPECT_EQ(cells.pair_count(), 2u);
}

// In space an interior particle of the cubic lattice has 32 bonds (the
// shells at l0, sqrt 2, sqrt 3 and 2 l0: 6 + 12 + 8 + 6) whose weights sum
// to the lattice's n0; the table holds r0 in three components.
TEST(BondTable, InteriorParticleInSpaceHas32Bonds) {
  ParticleStore p;
  p.dimension = 3;
  const int side = 7;
  const double l0 = 2e-3;
  p.resize(side * side * side);
  for (int c = 0, i = 0; c < side; ++c)
    for (int b = 0; b < side; ++b)
      for (int a = 0; a < side; ++a, ++i) {
        p.x0[i] = a * l0;
        p.y0[i] = b * l0;
        p.z0[i] = c * l0;
        p.id[i] = i;
      }
  const BondGeometry g = bond_geometry_3d(l0);
  EXPECT_DOUBLE_EQ(g.volume, l0 * l0 * l0);
  const BondTable bonds = build_bonds(p, g);
  const std::size_t centre = (3 * side + 3) * side + 3;
  ASSERT_EQ(bonds.end(centre) - bonds.begin(centre), 32u);
  double n = 0.0;
  for (std::uint32_t b = bonds.begin(centre); b < bonds.end(centre); ++b) {
    const std::size_t j = bonds.neighbor[b];
    EXPECT_EQ(bonds.r0z[b], p.z0[j] - p.z0[centre]);
    n += bond_math::weight(std::sqrt(bonds.r0x[b] * bonds.r0x[b] + bonds.r0y[b] * bonds.r0y[b] +
                                     bonds.r0z[b] * bonds.r0z[b]),
                           g.re);
  }
  EXPECT_NEAR(n, bond_math::lattice_number_density_3d(l0, g.re), 1e-12 * n);
  // The z components enter the hash: the same lattice turned is another table.
  ParticleStore turned = p;
  std::swap(turned.y0, turned.z0);
  const BondTable other = build_bonds(turned, g);
  EXPECT_EQ(other.neighbor.size(), bonds.neighbor.size());
  EXPECT_NE(other.hash(), bonds.hash());
  EXPECT_EQ(build_bonds(p, g, NeighborMethod::kdtree).hash(), bonds.hash());
}

TEST(BondTable, SameFromEverySearch) {
  Simulation sim(testing::rod_case({"l0=0.001"}));
  const ParticleStore& p = sim.particles();
  const BondGeometry g = sim.state().bonds.geometry;
  const BondTable cells = build_bonds(p, g, NeighborMethod::cell_list);
  const BondTable tree = build_bonds(p, g, NeighborMethod::kdtree);
  EXPECT_EQ(cells.hash(), tree.hash());
  EXPECT_EQ(cells.neighbor, tree.neighbor);
  EXPECT_EQ(cells.r0x, tree.r0x);
  EXPECT_EQ(cells.r0y, tree.r0y);
  EXPECT_TRUE(cells.r0z.empty());
}

}  // namespace
}  // namespace mpsolid
