#pragma once
// Each bond once. The bond table stores every bond from both ends (CSR), which
// is what a gather needs; the per-bond work (rotation, r_ij, u_ij, 1 / |r_ij|)
// is done once per bond, by its lower end (the owner), into the bond's slot,
// and both ends gather from it. Every per-bond operation is symmetric under
// i <-> j (bond_math.hpp), so a slot holds the bits each end computed for
// itself before: the same results, with half the arithmetic.
//
// Slot layout, chosen so that the hot loops run over contiguous memory:
// - dense slots: for each common index offset o = j - i > 0 (a "direction"),
//   one array of slots over a span of owners that have a bond of that
//   offset, bond (i, i + o) at base + i - first. A lattice body stored row
//   by row has the same offsets at every interior particle, so the owner
//   pass is a unit-stride loop per direction, and a body's own offsets (a
//   plate whose rows are longer than the rod's) cost only its span; one
//   offset used by two bodies far apart in storage has a span in each. A
//   dense slot without a bond is computed and never read.
// - extra slots: bonds whose offset is no direction (between bodies, a few
//   per body), after the dense ones, with their owner and partner listed.
// Particles whose rows have one pattern of offsets (a lattice interior)
// form runs: the k-th entry of particle m reads slot shift_k + m, the same
// shift for every m of the run, so a gather loops over m with unit stride.
// Other particles use the per-entry slot index. Either way a particle adds
// its bonds in CSR order: the same bits at any thread count, on either path.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "kernels/lanes.hpp"
#include "src/core/bonds.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

struct BondSlots {
  // The gather of a run: entry k of particle m reads slot slot_shift[k] + m
  // and partner m + partner_shift[k]; m owns the bond when partner_shift > 0.
  struct Pattern {
    std::vector<std::ptrdiff_t> slot_shift;
    std::vector<std::ptrdiff_t> partner_shift;
  };
  // Consecutive particles [begin, end) on one path; pattern < 0: per entry.
  struct Run {
    std::size_t begin = 0, end = 0;
    std::int32_t pattern = -1;
  };

  // The bonds (i, i + offset) for owners i in [first, last), at slots
  // base + i - first.
  struct Direction {
    std::size_t offset = 0, first = 0, last = 0, base = 0;
    std::size_t slot(std::size_t owner) const { return base + owner - first; }
  };

  std::size_t particles = 0;
  std::vector<Direction> directions;                      // by offset, then span
  std::size_t dense_slots = 0;                            // the directions' spans together
  std::vector<std::uint32_t> extra_owner, extra_partner;  // slot dense_slots + k, by owner
  std::vector<std::uint32_t> entry_slot;                  // slot of each bond table entry
  std::vector<Pattern> patterns;
  std::vector<Run> runs;  // cover [0, particles) in order

  std::size_t slot_count() const { return dense_slots + extra_owner.size(); }
};

// Per-slot arrays in one buffer. Each array starts at another offset modulo
// 4 KiB (a stagger of 5 cache lines), so that the dozen streams of one loop
// neither crowd into the same L1 sets nor alias 4 KiB apart, as separate
// page-aligned vectors of one size would.
class SlotArrays {
 public:
  SlotArrays() = default;
  SlotArrays(std::size_t arrays, std::size_t count)
      : stride_((count + 511) / 512 * 512 + 40), data_(arrays * stride_, 0.0) {}
  double* operator[](std::size_t k) { return data_.data() + k * stride_; }
  const double* operator[](std::size_t k) const { return data_.data() + k * stride_; }

 private:
  std::size_t stride_ = 0;
  std::vector<double> data_;
};

// Directions: each offset's owners cut into spans where two lie more than
// 64 apart; a span with at least 16 bonds, owned by at least an eighth of
// its particles (fewer would leave most of its array empty), is dense.
// Patterns: rows shared by at least 16 particles whose bonds all have
// dense slots.
BondSlots make_bond_slots(const BondTable& bonds);

// A per-slot copy of a per-entry quantity that is the same from both ends of
// a bond (a coefficient), taken from the owner's entry; 0 in empty slots.
std::vector<double> slot_values(const BondSlots& slots, const BondTable& bonds,
                                const std::vector<double>& per_entry);
// The same, written into a slot array (`out`: slot_count() values; empty
// slots are left as they are).
void fill_slot_array(const BondSlots& slots, const BondTable& bonds,
                     const std::vector<double>& per_entry, double* out);

// The dense part of the owner pass over the bonds owned by particles in
// `owners` whose partner is in `partners`, except the bonds between two
// particles below `fixed_end` (walls: stored first, never moving): for each
// direction, dense(count, slot, i, j) for `count` consecutive owners from i
// in its span (partners from j = i + o, slots from `slot`).
template <class Dense>
void for_each_dense_slot(const BondSlots& s, Range owners, std::size_t fixed_end, Dense&& dense,
                         Range partners = {0, static_cast<std::size_t>(-1)}) {
  const std::size_t n = s.particles;
  for (const BondSlots::Direction& d : s.directions) {
    const std::size_t o = d.offset;
    // Owners below fixed_end - o have their partner below fixed_end too.
    const std::size_t lowest = std::max(fixed_end, partners.begin);
    const std::size_t highest = std::min(n, partners.end);
    const std::size_t begin =
        std::max({owners.begin, d.first, lowest > o ? lowest - o : std::size_t{0}});
    const std::size_t end =
        std::min({owners.end, d.last, highest > o ? highest - o : std::size_t{0}});
    if (begin < end) dense(end - begin, d.slot(begin), begin, begin + o);
  }
}

// The extra bonds owned by particles in `owners`: [first, last) into
// extra_owner, extra_partner (slots dense_slots + k).
inline std::pair<std::size_t, std::size_t> owned_extras(const BondSlots& s, Range owners) {
  const auto at = [&](std::size_t i) {
    return static_cast<std::size_t>(std::lower_bound(s.extra_owner.begin(), s.extra_owner.end(),
                                                     static_cast<std::uint32_t>(i)) -
                                    s.extra_owner.begin());
  };
  return {at(owners.begin), at(owners.end)};
}

// The whole owner pass: for_each_dense_slot, then extra(slot, i, j) for each
// extra bond owned there (but those between two particles below fixed_end),
// both for partners in `partners`.
template <class Dense, class Extra>
void for_each_owned_slot(const BondSlots& s, Range owners, std::size_t fixed_end, Dense&& dense,
                         Extra&& extra, Range partners = {0, static_cast<std::size_t>(-1)}) {
  for_each_dense_slot(s, owners, fixed_end, dense, partners);
  const auto [first, last] = owned_extras(s, owners);
  for (std::size_t k = first; k < last; ++k) {
    const std::size_t j = s.extra_partner[k];
    if (j >= fixed_end && j >= partners.begin && j < partners.end)
      extra(s.dense_slots + k, s.extra_owner[k], j);
  }
}

// The pieces of `block` by path: regular(begin, end, pattern) for the parts
// of pattern runs, irregular(begin, end) for the rest, in index order.
// Patterns: BondSlots, or anything with its `runs` and `patterns`.
template <class Patterns, class Regular, class Irregular>
void for_each_run(const Patterns& s, Range block, Regular&& regular, Irregular&& irregular) {
  auto run = std::upper_bound(s.runs.begin(), s.runs.end(), block.begin,
                              [](std::size_t i, const auto& r) { return i < r.end; });
  for (; run != s.runs.end() && run->begin < block.end; ++run) {
    const std::size_t b = std::max(run->begin, block.begin), e = std::min(run->end, block.end);
    if (run->pattern < 0)
      irregular(b, e);
    else
      regular(b, e, s.patterns[static_cast<std::size_t>(run->pattern)]);
  }
}

// A gather over the particles of `block`, each adding its bonds in CSR
// order. On pattern runs of at least kLanes particles, kLanes particles at a
// time: lanes(m, pattern, first) for particles m .. m + kLanes - 1, whose
// k-th entries read slot m + slot_shift[k] and partner m + partner_shift[k]
// (unit stride across the lanes). The last group of a run overlaps the one
// before it; its lanes from `first` on are new (first is 0 otherwise). A
// kernel that only overwrites its particles' outputs may ignore `first`: a
// particle done twice gets the same bits twice. Each other particle: row(i).
template <class Patterns, class Group, class Row>
void gather_lanes(const Patterns& s, Range block, Group&& lanes, Row&& row) {
  for_each_run(
      s, block,
      [&](std::size_t begin, std::size_t end, const auto& pattern) {
        if (end - begin < kLanes) {
          for (std::size_t i = begin; i < end; ++i) row(i);
          return;
        }
        for (std::size_t m = begin; m < end; m += kLanes) {
          const std::size_t at = std::min(m, end - kLanes);
          lanes(at, pattern, m - at);
        }
      },
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) row(i);
      });
}

}  // namespace mpsolid
