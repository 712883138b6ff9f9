#include "src/distributed/bond_table_facts.hpp"

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

// The hash going on from `value` through every rank's bytes in rank order:
// rank r takes rank r - 1's value, adds its own and hands it on, in one
// collective round per rank (every rank makes the same calls, as the
// threads as ranks need); every rank gets the last rank's value.
std::uint64_t hash_in_rank_order(const RankGroup& world, std::uint64_t value,
                                 const std::function<void(Fnv1a&)>& add_mine) {
  for (int turn = 0; turn < world.size(); ++turn) {
    std::vector<double> mine;
    if (turn == world.rank()) {
      Fnv1a h(value);
      add_mine(h);
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
  const Range owned = layout.owned;
  const std::uint32_t first = owned.empty() ? 0 : local.begin(owned.begin);
  const std::uint32_t end = owned.empty() ? 0 : local.begin(owned.end);
  // The entries of the ranks before this one: where its rows start.
  const std::vector<double> counts = world.all_gather({static_cast<double>(end - first)});
  std::uint64_t before = 0, total = 0;
  for (int k = 0; k < world.size(); ++k) {
    const auto n = static_cast<std::uint64_t>(counts[static_cast<std::size_t>(k)]);
    if (k < world.rank()) before += n;
    total += n;
  }
  const bool last = world.rank() == world.size() - 1;
  std::uint64_t h = Fnv1a().value();
  // offsets: each owned row's start, and after the last rank's rows the end.
  h = hash_in_rank_order(world, h, [&](Fnv1a& f) {
    for (std::size_t i = owned.begin; i < owned.end; ++i)
      f.value(static_cast<std::uint32_t>(before + (local.begin(i) - first)));
    if (last) f.value(static_cast<std::uint32_t>(total));
  });
  // neighbor: global storage indices.
  h = hash_in_rank_order(world, h, [&](Fnv1a& f) {
    for (std::uint32_t k = first; k < end; ++k) f.value(layout.global_of[local.neighbor[k]]);
  });
  // In space (a rank with no bond has no r0z to tell it).
  const bool space = world.max(local.r0z.empty() ? 0 : 1) == 1;
  for (const std::vector<double>* v : {&local.r0x, &local.r0y, &local.r0z}) {
    if (v == &local.r0z && !space) break;  // the plane's hash as it always was
    h = hash_in_rank_order(
        world, h, [&](Fnv1a& f) { f.bytes(v->data() + first, (end - first) * sizeof(double)); });
  }
  return {static_cast<std::size_t>(total / 2), h};
}

}  // namespace mpsolid
