#pragma once
// Reproducible global sums: the index range is cut into fixed chunks (not one
// per thread), each chunk is summed serially, and the chunk sums are added in
// chunk order. The result is the same bits at any thread count.
#include <array>
#include <cstddef>
#include <vector>

#include "src/parallel.hpp"

namespace mpsolid {

inline constexpr std::size_t kSumChunk = 512;

// Sums term(i) (an std::array<double, N>) over [begin, end).
template <std::size_t N, class Term>
std::array<double, N> ordered_sum(std::size_t begin, std::size_t end, Term&& term) {
  std::array<double, N> total{};
  if (begin >= end) return total;
  const std::size_t chunks = (end - begin + kSumChunk - 1) / kSumChunk;
  std::vector<std::array<double, N>> partial(chunks);
  parallel_for(0, chunks, [&](std::size_t c) {
    std::array<double, N> s{};
    const std::size_t b = begin + c * kSumChunk;
    const std::size_t e = b + kSumChunk < end ? b + kSumChunk : end;
    for (std::size_t i = b; i < e; ++i) {
      const std::array<double, N> t = term(i);
      for (std::size_t k = 0; k < N; ++k) s[k] += t[k];
    }
    partial[c] = s;
  });
  for (const auto& s : partial)
    for (std::size_t k = 0; k < N; ++k) total[k] += s[k];
  return total;
}

}  // namespace mpsolid
