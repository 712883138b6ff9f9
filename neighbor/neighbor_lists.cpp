#include "neighbor/neighbor_lists.hpp"

namespace mpsolid {

NeighborLists find_neighbors(std::span<const double> x, std::span<const double> y, double radius,
                             NeighborMethod method) {
  switch (method) {
    case NeighborMethod::kdtree:
      return find_neighbors_kdtree(x, y, radius);
    case NeighborMethod::brute_force:
      return find_neighbors_brute_force(x, y, radius);
    case NeighborMethod::cell_list:
      break;
  }
  return find_neighbors_cell_list(x, y, radius);
}

}  // namespace mpsolid
