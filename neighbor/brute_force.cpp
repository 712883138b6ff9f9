// Brute-force neighbour search: every pair, O(n^2). The obviously correct
// oracle for the cell list and the k-d tree.
#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

NeighborLists find_neighbors_brute_force(const PointCloud& p, double radius) {
  const double re2 = radius * radius;
  return with_dimension(p, [&]<int Dim>() {
    return build_neighbor_lists(p.size(), [&](std::size_t i, auto&& emit) {
      for (std::size_t j = 0; j < p.size(); ++j)
        if (j != i && within_radius<Dim>(p, i, j, re2)) emit(j);
    });
  });
}

}  // namespace mpsolid
