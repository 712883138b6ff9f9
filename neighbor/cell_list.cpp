// Cell-list neighbour search, in the plane or in space. Cells of side >=
// radius; particles are binned by a stable counting sort (serial, in index
// order), so the candidate order never depends on thread timing.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
template <int Dim>
struct CellGrid {
  using Cell = std::array<long, Dim>;
  std::array<double, Dim> low{};
  double cell = 1;
  Cell count{};                        // cells along each axis
  std::vector<std::uint32_t> start;    // one more than the cells
  std::vector<std::uint32_t> members;  // particle indices, cell by cell

  long along(int a, double v) const {
    return std::clamp(static_cast<long>((v - low[a]) / cell), 0L, count[a] - 1);
  }
  Cell cell_of(const PointCloud& p, std::size_t i) const {
    Cell c;
    for (int a = 0; a < Dim; ++a) c[a] = along(a, axis(p, a)[i]);
    return c;
  }
  // x fastest, then y, then z.
  std::size_t index(const Cell& c) const {
    long k = c[Dim - 1];
    for (int a = Dim - 2; a >= 0; --a) k = k * count[a] + c[a];
    return static_cast<std::size_t>(k);
  }
  std::size_t cells() const {
    std::size_t n = 1;
    for (const long c : count) n *= static_cast<std::size_t>(c);
    return n;
  }
};

template <int Dim>
CellGrid<Dim> bin_points(const PointCloud& p, double radius) {
  CellGrid<Dim> g;
  std::array<double, Dim> extent{};
  // The 1e-12 margin keeps a pair closer than radius at most one cell apart
  // despite rounding in the cell index.
  g.cell = radius * (1.0 + 1e-12);
  for (int a = 0; a < Dim; ++a) {
    const auto [lo, hi] = std::minmax_element(axis(p, a).begin(), axis(p, a).end());
    g.low[a] = *lo;
    extent[a] = *hi - *lo;
    // Cap the grid so a sparse cloud cannot allocate without bound; a larger
    // cell is still correct (more candidates).
    constexpr double kMaxCellsPerAxis = 1 << 14;
    g.cell = std::max(g.cell, extent[a] / kMaxCellsPerAxis);
  }
  const auto count_cells = [&] {
    for (int a = 0; a < Dim; ++a) g.count[a] = static_cast<long>(extent[a] / g.cell) + 1;
  };
  count_cells();
  // In space the per-axis cap still allows 4e12 cells: a few per point at most.
  if constexpr (Dim == 3)
    while (static_cast<double>(g.count[0]) * static_cast<double>(g.count[1]) *
               static_cast<double>(g.count[2]) >
           std::max(4096.0, 8.0 * static_cast<double>(p.size()))) {
      g.cell *= 1.25;
      count_cells();
    }
  std::vector<std::uint32_t> cell_of(p.size());
  g.start.assign(g.cells() + 1, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    cell_of[i] = static_cast<std::uint32_t>(g.index(g.cell_of(p, i)));
    ++g.start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c + 1 < g.start.size(); ++c) g.start[c + 1] += g.start[c];
  g.members.resize(p.size());
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < p.size(); ++i)
    g.members[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return g;
}

// Calls f(cell) for the cells next to `home` (itself included) inside the grid.
template <int Dim, class F>
void for_each_adjacent_cell(const CellGrid<Dim>& g, const typename CellGrid<Dim>::Cell& home,
                            F&& f) {
  typename CellGrid<Dim>::Cell lo, hi, c;
  for (int a = 0; a < Dim; ++a) {
    lo[a] = std::max(home[a] - 1, 0L);
    hi[a] = std::min(home[a] + 1, g.count[a] - 1);
  }
  c = lo;
  while (true) {
    f(g.index(c));
    int a = 0;
    while (a < Dim && c[a] == hi[a]) c[a] = lo[a], ++a;
    if (a == Dim) return;
    ++c[a];
  }
}
}  // namespace

NeighborLists find_neighbors_cell_list(const PointCloud& p, double radius) {
  if (p.size() == 0) return build_neighbor_lists(0, [](std::size_t, auto&&) {});
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("neighbour radius must be positive and finite");
  const double re2 = radius * radius;
  return with_dimension(p, [&]<int Dim>() {
    const CellGrid<Dim> g = bin_points<Dim>(p, radius);
    return build_neighbor_lists(p.size(), [&](std::size_t i, auto&& emit) {
      for_each_adjacent_cell(g, g.cell_of(p, i), [&](std::size_t c) {
        for (std::uint32_t k = g.start[c]; k < g.start[c + 1]; ++k) {
          const std::size_t j = g.members[k];
          if (j != i && within_radius<Dim>(p, i, j, re2)) emit(j);
        }
      });
    });
  });
}

}  // namespace mpsolid
