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
  std::int64_t cx, cy, cz;  // cz 0 in the plane
  std::uint32_t index;
};
bool cell_before(const CellEntry& a, const CellEntry& b) {
  return std::tie(a.cx, a.cy, a.cz) < std::tie(b.cx, b.cy, b.cz);
}
}  // namespace

NeighborLists find_neighbors_sparse_cells(const PointCloud& p, double radius) {
  if (p.size() == 0) return build_neighbor_lists(0, [](std::size_t, auto&&) {});
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("neighbour radius must be positive and finite");
  const int dims = p.in_space() ? 3 : 2;
  for (int a = 0; a < dims; ++a)
    for (const double v : axis(p, a))
      if (!std::isfinite(v)) throw std::invalid_argument("neighbour search: a point is not finite");
  double low[3] = {0, 0, 0};
  for (int a = 0; a < dims; ++a) low[a] = *std::min_element(axis(p, a).begin(), axis(p, a).end());
  // The 1e-12 margin keeps a pair closer than radius at most one cell apart
  // despite rounding in the cell index.
  const double cell = radius * (1.0 + 1e-12);
  const auto along = [&](int a, std::size_t i) {
    return a < dims ? static_cast<std::int64_t>(std::floor((axis(p, a)[i] - low[a]) / cell)) : 0;
  };
  const auto cell_of = [&](std::size_t i) {
    return CellEntry{along(0, i), along(1, i), along(2, i), static_cast<std::uint32_t>(i)};
  };
  std::vector<CellEntry> sorted(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) sorted[i] = cell_of(i);
  std::stable_sort(sorted.begin(), sorted.end(), cell_before);
  const double r2 = radius * radius;
  const std::int64_t reach_z = dims == 3 ? 1 : 0;
  return with_dimension(p, [&]<int Dim>() {
    return build_neighbor_lists(p.size(), [&](std::size_t i, auto&& emit) {
      const CellEntry home = cell_of(i);
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (std::int64_t dy = -1; dy <= 1; ++dy)
          for (std::int64_t dz = -reach_z; dz <= reach_z; ++dz) {
            const auto [first, last] = std::equal_range(
                sorted.begin(), sorted.end(),
                CellEntry{home.cx + dx, home.cy + dy, home.cz + dz, 0}, cell_before);
            for (auto e = first; e != last; ++e)
              if (e->index != i && within_radius<Dim>(p, i, e->index, r2)) emit(e->index);
          }
    });
  });
}

}  // namespace mpsolid
