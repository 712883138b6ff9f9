#pragma once
// Reproducible global sums: the index range is cut into fixed chunks (not one
// per thread), each chunk is summed serially, and the chunk sums are added in
// chunk order. The result is the same bits at any thread count. Called by
// every thread of a team, each thread sums it all alone (same chunks, same
// bits): the partial sums are locals, not shared.
#include <array>
#include <cstddef>
#include <vector>

#include "src/core/parallel.hpp"

namespace mpsolid {

inline constexpr std::size_t kSumChunk = 512;

// term(i) summed over [begin, end) in order from zero: one chunk's sum.
template <std::size_t N, class Term>
std::array<double, N> sum_in_order(std::size_t begin, std::size_t end, Term&& term) {
  std::array<double, N> s{};
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<double, N> t = term(i);
    for (std::size_t k = 0; k < N; ++k) s[k] += t[k];
  }
  return s;
}

// Sums term(i) (an std::array<double, N>) over [begin, end).
template <std::size_t N, class Term>
std::array<double, N> ordered_sum(std::size_t begin, std::size_t end, Term&& term) {
  std::array<double, N> total{};
  if (begin >= end) return total;
  const std::size_t chunks = (end - begin + kSumChunk - 1) / kSumChunk;
  std::vector<std::array<double, N>> partial(chunks);
  auto sum_chunk = [&](std::size_t c) {
    const std::size_t b = begin + c * kSumChunk;
    const std::size_t e = b + kSumChunk < end ? b + kSumChunk : end;
    partial[c] = sum_in_order<N>(b, e, term);
  };
  if (in_team())
    for (std::size_t c = 0; c < chunks; ++c) sum_chunk(c);
  else
    parallel_for(0, chunks, sum_chunk);
  for (const auto& s : partial)
    for (std::size_t k = 0; k < N; ++k) total[k] += s[k];
  return total;
}

}  // namespace mpsolid
