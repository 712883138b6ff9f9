// Sparse cell search: the points' cells (side >= radius) sorted by cell, so
// memory grows with the points, not with the area they span. The contact
// search uses it: bodies that fly apart spread the candidates over an area
// a dense grid (cell_list.cpp) would need gigabytes for.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <tuple>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
struct CellEntry {
  std::int64_t cx, cy;
  std::uint32_t index;
};
bool cell_before(const CellEntry& a, const CellEntry& b) {
  return std::tie(a.cx, a.cy) < std::tie(b.cx, b.cy);
}
}  // namespace

NeighborLists find_neighbors_sparse_cells(std::span<const double> x, std::span<const double> y,
                                          double radius) {
  if (x.empty()) return build_neighbor_lists(0, [](std::size_t, auto&&) {});
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("neighbour radius must be positive and finite");
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw std::invalid_argument("neighbour search: a point is not finite");
  const double xmin = *std::min_element(x.begin(), x.end());
  const double ymin = *std::min_element(y.begin(), y.end());
  // The 1e-12 margin keeps a pair closer than radius at most one cell apart
  // despite rounding in the cell index.
  const double cell = radius * (1.0 + 1e-12);
  const auto cell_of = [&](std::size_t i) {
    return CellEntry{static_cast<std::int64_t>(std::floor((x[i] - xmin) / cell)),
                     static_cast<std::int64_t>(std::floor((y[i] - ymin) / cell)),
                     static_cast<std::uint32_t>(i)};
  };
  std::vector<CellEntry> sorted(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) sorted[i] = cell_of(i);
  std::stable_sort(sorted.begin(), sorted.end(), cell_before);
  const double r2 = radius * radius;
  return build_neighbor_lists(x.size(), [&](std::size_t i, auto&& emit) {
    const CellEntry home = cell_of(i);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const auto [first, last] = std::equal_range(
            sorted.begin(), sorted.end(), CellEntry{home.cx + dx, home.cy + dy, 0}, cell_before);
        for (auto e = first; e != last; ++e)
          if (e->index != i && within_radius(x[i], y[i], x[e->index], y[e->index], r2))
            emit(e->index);
      }
  });
}

}  // namespace mpsolid
