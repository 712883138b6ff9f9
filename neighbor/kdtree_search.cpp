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
  const PointCloud& points;
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return axis(points, static_cast<int>(dim))[i];
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};
template <int Dim>
using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, SoaCloud>,
                                                 SoaCloud, Dim, std::size_t>;
}  // namespace

NeighborLists find_neighbors_kdtree(const PointCloud& p, double radius) {
  const SoaCloud cloud{p};
  const double re2 = radius * radius;
  // Search slightly wider, then decide with the shared predicate: nanoflann's
  // own distance arithmetic must not decide borderline pairs.
  const double search_radius2 = re2 * (1.0 + 1e-9);
  nanoflann::SearchParams params;
  params.sorted = false;
  return with_dimension(p, [&]<int Dim>() {
    Tree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    tree.buildIndex();
    return build_neighbor_lists(p.size(), [&](std::size_t i, auto&& emit) {
      std::vector<std::pair<std::size_t, double>> found;
      double query[Dim];
      for (int a = 0; a < Dim; ++a) query[a] = axis(p, a)[i];
      tree.radiusSearch(query, search_radius2, found, params);
      for (const auto& [j, d2] : found)
        if (j != i && within_radius<Dim>(p, i, j, re2)) emit(j);
    });
  });
}

}  // namespace mpsolid
