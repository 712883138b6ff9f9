#pragma once
// Neighbour lists in compressed rows (CSR): the neighbours of point i are
// indices[offsets[i] .. offsets[i+1]), in ascending index order. This is the
// canonical order every search returns, so their outputs compare with ==.
#include <cstdint>
#include <span>
#include <vector>

namespace mpsolid {

struct NeighborLists {
  std::vector<std::uint32_t> offsets;  // size n + 1
  std::vector<std::uint32_t> indices;

  std::size_t point_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  std::size_t pair_count() const { return indices.size(); }
  bool operator==(const NeighborLists&) const = default;
};

// Builds canonical CSR lists from per-point candidate generation. `visit(i,
// emit)` must call emit(j) for every neighbour j of i (any order, no
// duplicates); rows are then sorted. Runs visit twice (count, then fill) so
// no per-point allocation is needed; rows are built in parallel.
template <class Visit>
NeighborLists build_neighbor_lists(std::size_t n, Visit&& visit);

enum class NeighborMethod { cell_list, kdtree, brute_force };

// All three give identical lists for the same points and radius.
NeighborLists find_neighbors(std::span<const double> x, std::span<const double> y, double radius,
                             NeighborMethod method = NeighborMethod::cell_list);
NeighborLists find_neighbors_cell_list(std::span<const double> x, std::span<const double> y,
                                       double radius);
NeighborLists find_neighbors_kdtree(std::span<const double> x, std::span<const double> y,
                                    double radius);
// Cells sorted by index instead of a dense grid: memory in the points, not
// in the area they span (the contact search, whose bodies may fly apart).
NeighborLists find_neighbors_sparse_cells(std::span<const double> x, std::span<const double> y,
                                          double radius);
NeighborLists find_neighbors_brute_force(std::span<const double> x, std::span<const double> y,
                                         double radius);

}  // namespace mpsolid

#include "neighbor/neighbor_lists_impl.hpp"
