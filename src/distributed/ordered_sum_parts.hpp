#pragma once
// An ordered sum (src/core/ordered_sum.hpp) computed by ranks that each hold
// some contiguous pieces of its range, with the serial sum's bits. The
// serial sum cuts [begin, end) into chunks of kSumChunk from `begin`, sums
// each chunk's terms in order from zero and adds the chunk sums in chunk
// order. A rank sends the sums of the chunks wholly inside one of its
// pieces and, for a chunk its piece shares with others, its terms in order;
// every rank's pieces, put in serial order, finish each shared chunk from
// zero in the serial order. A cut need not fall on the sum's chunks, so one
// cut serves sums over different ranges (all particles, the moving ones).
#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "src/core/ordered_sum.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid {

template <std::size_t N>
struct OrderedSumPart {
  // A chunk's sum (whole), or the terms of this part's share of it in order.
  struct Piece {
    std::size_t chunk = 0;
    std::size_t first = 0;  // the serial index of its first term
    bool whole = false;
    std::vector<std::array<double, N>> values;
  };
  std::vector<Piece> pieces;  // in chunk order

  // As doubles for a message: per piece its chunk, its first index, its
  // value count (0 for a whole chunk's one sum) and its values.
  void append_to(std::vector<double>& out) const {
    out.push_back(static_cast<double>(pieces.size()));
    for (const Piece& p : pieces) {
      out.push_back(static_cast<double>(p.chunk));
      out.push_back(static_cast<double>(p.first));
      out.push_back(p.whole ? 0.0 : static_cast<double>(p.values.size()));
      for (const auto& v : p.values) out.insert(out.end(), v.begin(), v.end());
    }
  }
  static OrderedSumPart read(const std::vector<double>& in, std::size_t& at) {
    OrderedSumPart part;
    const auto take = [&] {
      if (at >= in.size()) throw std::runtime_error("an ordered sum's part cut short");
      return in[at++];
    };
    part.pieces.resize(static_cast<std::size_t>(take()));
    for (Piece& p : part.pieces) {
      p.chunk = static_cast<std::size_t>(take());
      p.first = static_cast<std::size_t>(take());
      const auto count = static_cast<std::size_t>(take());
      p.whole = count == 0;
      p.values.resize(p.whole ? 1 : count);
      for (auto& v : p.values)
        for (double& x : v) x = take();
    }
    return part;
  }
};

// The pieces of [from, to) (within [begin, end)) onto `part`.
template <std::size_t N, class Term>
void append_ordered_sum_pieces(std::size_t begin, std::size_t end, std::size_t from, std::size_t to,
                               Term& term, OrderedSumPart<N>& part) {
  for (std::size_t b = from; b < to;) {
    const std::size_t chunk = (b - begin) / kSumChunk;
    const std::size_t chunk_begin = begin + chunk * kSumChunk;
    const std::size_t chunk_end = std::min(end, chunk_begin + kSumChunk);
    const std::size_t e = std::min(to, chunk_end);
    typename OrderedSumPart<N>::Piece piece;
    piece.chunk = chunk;
    piece.first = b;
    piece.whole = b == chunk_begin && e == chunk_end;
    if (piece.whole) {
      piece.values.push_back(sum_in_order<N>(b, e, term));
    } else {
      for (std::size_t i = b; i < e; ++i) piece.values.push_back(term(i));
    }
    part.pieces.push_back(std::move(piece));
    b = e;
  }
}

// The part of the ordered sum of term(i) over [begin, end) that the indices
// of `held` (ascending ranges) give (term takes the serial index).
template <std::size_t N, class Term>
OrderedSumPart<N> ordered_sum_part(std::size_t begin, std::size_t end,
                                   const std::vector<Range>& held, Term&& term) {
  OrderedSumPart<N> part;
  for (const Range r : held) {
    const std::size_t from = std::max(begin, r.begin), to = std::min(end, r.end);
    append_ordered_sum_pieces<N>(begin, end, from, to, term, part);
  }
  return part;
}
template <std::size_t N, class Term>
OrderedSumPart<N> ordered_sum_part(std::size_t begin, std::size_t end, Range held, Term&& term) {
  return ordered_sum_part<N>(begin, end, std::vector<Range>{held}, term);
}

// The sum from every rank's part: the serial bits when the parts cover
// [begin, end) once each (their pieces are put in serial order).
template <std::size_t N>
std::array<double, N> combine_ordered_sum(const std::vector<OrderedSumPart<N>>& parts) {
  std::vector<std::array<double, N>> chunk_sums;
  std::size_t open_chunk = 0;
  bool open = false;  // a shared chunk being summed
  std::array<double, N> running{};
  const auto close = [&] {
    if (open) chunk_sums.push_back(running);
    open = false;
  };
  std::vector<const typename OrderedSumPart<N>::Piece*> in_order;
  for (const OrderedSumPart<N>& part : parts)
    for (const auto& piece : part.pieces) in_order.push_back(&piece);
  std::stable_sort(in_order.begin(), in_order.end(),
                   [](const auto* a, const auto* b) { return a->first < b->first; });
  for (const auto* piece : in_order) {
    if (piece->whole) {
      close();
      chunk_sums.push_back(piece->values.front());
      continue;
    }
    if (!open || piece->chunk != open_chunk) {
      close();
      open = true;
      open_chunk = piece->chunk;
      running = {};
    }
    for (const auto& t : piece->values)
      for (std::size_t k = 0; k < N; ++k) running[k] += t[k];
  }
  close();
  std::array<double, N> total{};
  for (const auto& s : chunk_sums)
    for (std::size_t k = 0; k < N; ++k) total[k] += s[k];
  return total;
}

}  // namespace mpsolid
