#pragma once
// Template part of neighbor_lists.hpp.
#include <algorithm>

#include "src/core/parallel.hpp"

namespace mpsolid {

template <class Visit>
NeighborLists build_neighbor_lists(std::size_t n, Visit&& visit) {
  NeighborLists lists;
  std::vector<std::uint32_t> counts(n, 0);
  parallel_for(0, n, [&](std::size_t i) {
    std::uint32_t c = 0;
    visit(i, [&](std::size_t) { ++c; });
    counts[i] = c;
  });
  lists.offsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) lists.offsets[i + 1] = lists.offsets[i] + counts[i];
  lists.indices.resize(lists.offsets[n]);
  parallel_for(0, n, [&](std::size_t i) {
    std::uint32_t* row = lists.indices.data() + lists.offsets[i];
    std::uint32_t k = 0;
    visit(i, [&](std::size_t j) { row[k++] = static_cast<std::uint32_t>(j); });
    std::sort(row, row + k);
  });
  return lists;
}

}  // namespace mpsolid
