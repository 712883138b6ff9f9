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

// Points in the plane (z empty) or in space, one array per axis, read in
// place.
struct PointCloud {
  PointCloud(std::span<const double> x_, std::span<const double> y_,
             std::span<const double> z_ = {})
      : x(x_), y(y_), z(z_) {}
  std::span<const double> x, y, z;
  std::size_t size() const { return x.size(); }
  bool in_space() const { return !z.empty(); }
};

// All of them give identical lists for the same points and radius.
NeighborLists find_neighbors(const PointCloud& points, double radius,
                             NeighborMethod method = NeighborMethod::cell_list);
NeighborLists find_neighbors_cell_list(const PointCloud& points, double radius);
NeighborLists find_neighbors_kdtree(const PointCloud& points, double radius);
// Cells sorted by index instead of a dense grid: memory in the points, not
// in the area they span (the contact search, whose bodies may fly apart).
NeighborLists find_neighbors_sparse_cells(const PointCloud& points, double radius);
NeighborLists find_neighbors_brute_force(const PointCloud& points, double radius);

}  // namespace mpsolid

#include "neighbor/neighbor_lists_impl.hpp"
