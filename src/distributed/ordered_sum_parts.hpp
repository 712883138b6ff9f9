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
//
// A shared chunk is finished on the ranks (finish_shared_chunks): its
// running sum goes from the owner of each of its pieces to the next, each
// adding its terms in order, which is the serial sum's own order from zero;
// so a rank sends on only chunk sums, however finely the cut divides the
// chunks (bands divide most of them).
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "src/core/ordered_sum.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/rank_group.hpp"

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

// The part `mine` of the ordered sum over [begin, end) (ordered_sum_part
// over this rank's pieces of `d`) with every chunk that several pieces
// share finished over the ranks: in rounds, the owner of each shared
// chunk's k-th piece adds its terms to the running sum it got (zero for the
// first piece) and hands it to the owner of the next, the last owner
// keeping the chunk's sum. Collective over `world` (every rank makes the
// same exchanges: the rounds follow from `d`). What is left is only whole
// chunks' sums, the serial bits, each with its chunk's first index.
template <std::size_t N>
OrderedSumPart<N> finish_shared_chunks(const OrderedSumPart<N>& mine, std::size_t begin,
                                       std::size_t end, const Decomposition& d,
                                       const RankGroup& world) {
  using Value = std::array<double, N>;
  const int me = world.rank();
  // Every shared chunk's pieces in storage order: first index and owner.
  struct Segment {
    std::size_t first;
    int owner;
  };
  std::vector<std::vector<Segment>> shared;
  std::vector<std::size_t> shared_chunk;
  {
    std::vector<Segment> current;
    std::size_t current_chunk = std::numeric_limits<std::size_t>::max();
    const auto close = [&] {
      if (current.size() > 1) {
        shared.push_back(current);
        shared_chunk.push_back(current_chunk);
      }
      current.clear();
    };
    // The pieces that meet [begin, end): from the one holding `begin` on.
    for (std::size_t k = d.piece_of(begin); k + 1 < d.starts.size() && d.starts[k] < end; ++k) {
      const std::size_t b = std::max(begin, d.starts[k]), e = std::min(end, d.starts[k + 1]);
      const int owner = d.owners.empty() ? static_cast<int>(k) : d.owners[k];
      for (std::size_t at = b; at < e;) {
        const std::size_t chunk = (at - begin) / kSumChunk;
        if (chunk != current_chunk) {
          close();
          current_chunk = chunk;
        }
        current.push_back({at, owner});
        at = std::min(e, begin + (chunk + 1) * kSumChunk);
      }
    }
    close();
  }
  // This rank's terms of a piece starting at `first`, added onto v.
  const auto fold = [&](std::size_t first, Value v) {
    const auto at = std::lower_bound(mine.pieces.begin(), mine.pieces.end(), first,
                                     [](const auto& p, std::size_t f) { return p.first < f; });
    if (at == mine.pieces.end() || at->first != first || at->whole)
      throw std::logic_error("finish_shared_chunks: a piece of the cut without its terms");
    for (const Value& t : at->values)
      for (std::size_t k = 0; k < N; ++k) v[k] += t[k];
    return v;
  };
  std::size_t rounds = 0;
  for (const auto& s : shared) rounds = std::max(rounds, s.size() - 1);
  std::vector<Value> running(shared.size(), Value{});
  for (std::size_t k = 0; k < rounds; ++k) {
    std::map<int, std::vector<double>> out;
    std::map<int, std::size_t> expected;
    for (std::size_t c = 0; c < shared.size(); ++c) {
      const auto& s = shared[c];
      if (k + 1 >= s.size()) continue;
      if (s[k].owner == me) {
        running[c] = fold(s[k].first, running[c]);
        if (s[k + 1].owner != me) {
          std::vector<double>& to = out[s[k + 1].owner];
          to.insert(to.end(), running[c].begin(), running[c].end());
        }
      }
      if (s[k + 1].owner == me && s[k].owner != me) {
        expected[s[k].owner] += N;
        out[s[k].owner];  // the peer lists this rank too: an empty letter
      }
      if (s[k].owner == me && s[k + 1].owner != me) expected[s[k + 1].owner];
    }
    std::vector<int> peers;
    std::vector<std::vector<double>> letters, in;
    for (auto& [peer, letter] : out) {
      peers.push_back(peer);
      letters.push_back(std::move(letter));
      in.emplace_back(expected[peer]);
    }
    world.exchange(peers, letters, in);
    std::vector<std::size_t> read(peers.size(), 0);
    for (std::size_t c = 0; c < shared.size(); ++c) {
      const auto& s = shared[c];
      if (k + 1 >= s.size() || s[k + 1].owner != me || s[k].owner == me) continue;
      const auto p = static_cast<std::size_t>(
          std::lower_bound(peers.begin(), peers.end(), s[k].owner) - peers.begin());
      std::copy_n(in[p].begin() + static_cast<long>(read[p]), N, running[c].begin());
      read[p] += N;
    }
  }
  OrderedSumPart<N> done;
  for (const auto& piece : mine.pieces)
    if (piece.whole) done.pieces.push_back(piece);
  for (std::size_t c = 0; c < shared.size(); ++c)
    if (shared[c].back().owner == me) {
      typename OrderedSumPart<N>::Piece piece;
      piece.chunk = shared_chunk[c];
      piece.first = shared[c].front().first;
      piece.whole = true;
      piece.values.push_back(fold(shared[c].back().first, running[c]));
      done.pieces.push_back(std::move(piece));
    }
  std::sort(done.pieces.begin(), done.pieces.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return done;
}

}  // namespace mpsolid
