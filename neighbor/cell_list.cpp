// Cell-list neighbour search. Cells of side >= radius; particles are binned by
// a stable counting sort (serial, in index order), so the candidate order never
// depends on thread timing.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
struct CellGrid {
  double xmin = 0, ymin = 0, cell = 1;
  long nx = 1, ny = 1;
  std::vector<std::uint32_t> start;    // size nx*ny + 1
  std::vector<std::uint32_t> members;  // particle indices, cell by cell

  long cell_x(double x) const {
    return std::clamp(static_cast<long>((x - xmin) / cell), 0L, nx - 1);
  }
  long cell_y(double y) const {
    return std::clamp(static_cast<long>((y - ymin) / cell), 0L, ny - 1);
  }
};

CellGrid bin_points(std::span<const double> x, std::span<const double> y, double radius) {
  CellGrid g;
  const auto [xlo, xhi] = std::minmax_element(x.begin(), x.end());
  const auto [ylo, yhi] = std::minmax_element(y.begin(), y.end());
  g.xmin = *xlo;
  g.ymin = *ylo;
  // Cap the grid so a sparse cloud cannot allocate without bound; a larger
  // cell is still correct (more candidates).
  constexpr double kMaxCellsPerAxis = 1 << 14;
  // The 1e-12 margin keeps a pair closer than radius at most one cell apart
  // despite rounding in the cell index.
  g.cell = std::max(
      {radius * (1.0 + 1e-12), (*xhi - *xlo) / kMaxCellsPerAxis, (*yhi - *ylo) / kMaxCellsPerAxis});
  g.nx = static_cast<long>((*xhi - *xlo) / g.cell) + 1;
  g.ny = static_cast<long>((*yhi - *ylo) / g.cell) + 1;
  const std::size_t cells = static_cast<std::size_t>(g.nx * g.ny);
  std::vector<std::uint32_t> cell_of(x.size());
  g.start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < x.size(); ++i) {
    cell_of[i] = static_cast<std::uint32_t>(g.cell_y(y[i]) * g.nx + g.cell_x(x[i]));
    ++g.start[cell_of[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) g.start[c + 1] += g.start[c];
  g.members.resize(x.size());
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < x.size(); ++i)
    g.members[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
  return g;
}
}  // namespace

NeighborLists find_neighbors_cell_list(std::span<const double> x, std::span<const double> y,
                                       double radius) {
  if (x.empty()) return build_neighbor_lists(0, [](std::size_t, auto&&) {});
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("neighbour radius must be positive and finite");
  const CellGrid g = bin_points(x, y, radius);
  const double re2 = radius * radius;
  return build_neighbor_lists(x.size(), [&](std::size_t i, auto&& emit) {
    const long cx = g.cell_x(x[i]), cy = g.cell_y(y[i]);
    for (long ny = std::max(cy - 1, 0L); ny <= std::min(cy + 1, g.ny - 1); ++ny)
      for (long nx = std::max(cx - 1, 0L); nx <= std::min(cx + 1, g.nx - 1); ++nx) {
        const std::size_t c = static_cast<std::size_t>(ny * g.nx + nx);
        for (std::uint32_t k = g.start[c]; k < g.start[c + 1]; ++k) {
          const std::size_t j = g.members[k];
          if (j != i && within_radius(x[i], y[i], x[j], y[j], re2)) emit(j);
        }
      }
  });
}

}  // namespace mpsolid
