#include "neighbor/neighbor_lists.hpp"

namespace mpsolid {

NeighborLists find_neighbors(const PointCloud& points, double radius, NeighborMethod method) {
  switch (method) {
    case NeighborMethod::kdtree:
      return find_neighbors_kdtree(points, radius);
    case NeighborMethod::brute_force:
      return find_neighbors_brute_force(points, radius);
    case NeighborMethod::cell_list:
      break;
  }
  return find_neighbors_cell_list(points, radius);
}

}  // namespace mpsolid
