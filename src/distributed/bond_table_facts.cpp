#include "src/distributed/bond_table_facts.hpp"

#include <algorithm>
#include <functional>
#include <vector>

#include "src/core/hash.hpp"

namespace mpsolid {

namespace {
// 64 bits as two exact doubles, and back.
void append_bits(std::uint64_t v, std::vector<double>& out) {
  out.push_back(static_cast<double>(v >> 32));
  out.push_back(static_cast<double>(v & 0xffffffffu));
}
std::uint64_t read_bits(const std::vector<double>& in, std::size_t at) {
  return (static_cast<std::uint64_t>(in.at(at)) << 32) | static_cast<std::uint64_t>(in.at(at + 1));
}

// Every rank's owned pieces in storage order: each one's first storage
// index, its rank, its place among that rank's pieces and its bond entries.
struct PieceTurn {
  double start, rank, index, entries;
};
std::vector<PieceTurn> pieces_in_order(const RankGroup& world, const std::vector<double>& entries,
                                       const LocalLayout& layout) {
  std::vector<double> mine{static_cast<double>(entries.size())};
  for (std::size_t k = 0; k < entries.size(); ++k)
    mine.insert(mine.end(),
                {static_cast<double>(layout.owned_pieces[k].begin),
                 static_cast<double>(world.rank()), static_cast<double>(k), entries[k]});
  const std::vector<double> all = world.all_gather(mine);
  std::vector<PieceTurn> turns;
  for (std::size_t at = 0; at < all.size();) {
    const auto n = static_cast<std::size_t>(all[at++]);
    for (std::size_t k = 0; k < n; ++k, at += 4)
      turns.push_back({all[at], all[at + 1], all[at + 2], all[at + 3]});
  }
  std::stable_sort(turns.begin(), turns.end(),
                   [](const PieceTurn& x, const PieceTurn& y) { return x.start < y.start; });
  return turns;
}

// The hash going on from `value` through every piece's bytes in storage
// order: the owner of each takes the value so far, adds the piece's bytes
// and hands it on, in one collective round per piece (every rank makes the
// same calls, as the threads as ranks need); every rank gets the last
// value.
std::uint64_t hash_in_piece_order(const RankGroup& world, const std::vector<PieceTurn>& turns,
                                  std::uint64_t value,
                                  const std::function<void(std::size_t, Fnv1a&)>& add_piece) {
  for (const PieceTurn& turn : turns) {
    std::vector<double> mine;
    if (static_cast<int>(turn.rank) == world.rank()) {
      Fnv1a h(value);
      add_piece(static_cast<std::size_t>(turn.index), h);
      append_bits(h.value(), mine);
    }
    value = read_bits(world.all_gather(mine), 0);
  }
  return value;
}
}  // namespace

void BondTableFacts::append_to(std::vector<double>& out) const {
  out.push_back(static_cast<double>(count));
  append_bits(hash, out);
}

BondTableFacts BondTableFacts::read(const std::vector<double>& in, std::size_t& at) {
  BondTableFacts f{static_cast<std::size_t>(in.at(at)), read_bits(in, at + 1)};
  at += 3;
  return f;
}

BondTableFacts bond_table_facts(const BondTable& local, const LocalLayout& layout,
                                const RankGroup& world) {
  // Each owned piece's rows: local [row_begin, row_end), entries [first, end).
  const std::size_t pieces = layout.owned_pieces.size();
  std::vector<std::size_t> row_begin(pieces), row_end(pieces);
  std::vector<double> entries(pieces);
  for (std::size_t k = 0; k < pieces; ++k) {
    row_begin[k] = layout.piece_local[k];
    row_end[k] = row_begin[k] + layout.owned_pieces[k].size();
    entries[k] = static_cast<double>(local.begin(row_end[k]) - local.begin(row_begin[k]));
  }
  const std::vector<PieceTurn> turns = pieces_in_order(world, entries, layout);
  // The entries before each of this rank's pieces, and in all.
  std::vector<std::uint64_t> before(pieces, 0);
  std::uint64_t total = 0;
  for (const PieceTurn& t : turns) {
    if (static_cast<int>(t.rank) == world.rank()) before[static_cast<std::size_t>(t.index)] = total;
    total += static_cast<std::uint64_t>(t.entries);
  }
  const bool has_last = !turns.empty() && static_cast<int>(turns.back().rank) == world.rank();
  const std::size_t last = has_last ? static_cast<std::size_t>(turns.back().index) : pieces;
  std::uint64_t h = Fnv1a().value();
  // offsets: each owned row's start, and after the last piece's rows the end.
  h = hash_in_piece_order(world, turns, h, [&](std::size_t k, Fnv1a& f) {
    const std::uint32_t first = local.begin(row_begin[k]);
    for (std::size_t i = row_begin[k]; i < row_end[k]; ++i)
      f.value(static_cast<std::uint32_t>(before[k] + (local.begin(i) - first)));
    if (k == last) f.value(static_cast<std::uint32_t>(total));
  });
  // neighbor: global storage indices.
  h = hash_in_piece_order(world, turns, h, [&](std::size_t k, Fnv1a& f) {
    for (std::uint32_t e = local.begin(row_begin[k]); e < local.begin(row_end[k]); ++e)
      f.value(layout.global_of[local.neighbor[e]]);
  });
  // In space (a rank with no bond has no r0z to tell it).
  const bool space = world.max(local.r0z.empty() ? 0 : 1) == 1;
  for (const std::vector<double>* v : {&local.r0x, &local.r0y, &local.r0z}) {
    if (v == &local.r0z && !space) break;  // the plane's hash as it always was
    h = hash_in_piece_order(world, turns, h, [&](std::size_t k, Fnv1a& f) {
      const std::uint32_t first = local.begin(row_begin[k]), end = local.begin(row_end[k]);
      f.bytes(v->data() + first, (end - first) * sizeof(double));
    });
  }
  return {static_cast<std::size_t>(total / 2), h};
}

}  // namespace mpsolid
