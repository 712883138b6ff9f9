// Brute-force neighbour search: every pair, O(n^2). The obviously correct
// oracle for the cell list and the k-d tree.
#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

NeighborLists find_neighbors_brute_force(std::span<const double> x, std::span<const double> y,
                                         double radius) {
  const double re2 = radius * radius;
  return build_neighbor_lists(x.size(), [&](std::size_t i, auto&& emit) {
    for (std::size_t j = 0; j < x.size(); ++j)
      if (j != i && within_radius(x[i], y[i], x[j], y[j], re2)) emit(j);
  });
}

}  // namespace mpsolid
