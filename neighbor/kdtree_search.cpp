// k-d tree neighbour search with nanoflann (Debian's 1.4.3 API: SearchParams,
// squared radius). An independent cross-check of the cell list. nanoflann is
// used in this file only.
#include <nanoflann.hpp>

#include "neighbor/neighbor_lists.hpp"
#include "neighbor/pair_predicate.hpp"

namespace mpsolid {

namespace {
// Reads the solver's SoA coordinate arrays in place (no copy).
struct SoaCloud {
  std::span<const double> x, y;
  std::size_t kdtree_get_point_count() const { return x.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return dim == 0 ? x[i] : y[i]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SoaCloud>,
                                                 SoaCloud, 2, std::size_t>;
}  // namespace

NeighborLists find_neighbors_kdtree(std::span<const double> x, std::span<const double> y,
                                    double radius) {
  const SoaCloud cloud{x, y};
  Tree tree(2, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  tree.buildIndex();
  const double re2 = radius * radius;
  // Search slightly wider, then decide with the shared predicate: nanoflann's
  // own distance arithmetic must not decide borderline pairs.
  const double search_radius2 = re2 * (1.0 + 1e-9);
  nanoflann::SearchParams params;
  params.sorted = false;
  return build_neighbor_lists(x.size(), [&](std::size_t i, auto&& emit) {
    std::vector<std::pair<std::size_t, double>> found;
    const double query[2] = {x[i], y[i]};
    tree.radiusSearch(query, search_radius2, found, params);
    for (const auto& [j, d2] : found)
      if (j != i && within_radius(x[i], y[i], x[j], y[j], re2)) emit(j);
  });
}

}  // namespace mpsolid
