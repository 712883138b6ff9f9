#include "kernels/bond_slots.hpp"

#include <map>
#include <utility>
#include <vector>

namespace mpsolid {

namespace {
constexpr std::size_t kMinPatternParticles = 16;
constexpr std::size_t kDirectionShare = 8;  // a direction serves an eighth of its span
constexpr std::size_t kMinDirectionBonds = 16;
// Owners of one offset further apart than this belong to separate spans
// (two bodies whose rows have the same length, or a body and the bonds
// between two others).
constexpr std::size_t kSpanGap = 64;

// The direction of the bond (owner, owner + offset), or none.
class DirectionIndex {
 public:
  void add(const BondSlots::Direction& d) { of_[d.offset].push_back(d); }
  const BondSlots::Direction* find(std::size_t offset, std::size_t owner) const {
    const auto at = of_.find(offset);
    if (at == of_.end()) return nullptr;
    for (const BondSlots::Direction& d : at->second)
      if (owner >= d.first && owner < d.last) return &d;
    return nullptr;
  }

 private:
  std::map<std::size_t, std::vector<BondSlots::Direction>> of_;
};

// The dense directions: each offset's owners cut into spans at gaps wider
// than kSpanGap, and the spans with enough bonds.
DirectionIndex choose_directions(const BondTable& bonds, BondSlots& s) {
  struct Span {
    std::size_t count = 0, first = 0, last = 0;
  };
  std::map<std::size_t, std::vector<Span>> spans;
  for (std::size_t i = 0; i < bonds.particle_count(); ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      if (bonds.neighbor[b] < i) continue;
      std::vector<Span>& of = spans[bonds.neighbor[b] - i];
      if (of.empty() || i - of.back().last > kSpanGap) of.push_back({0, i, i});
      ++of.back().count;
      of.back().last = i + 1;
    }
  DirectionIndex index;
  for (const auto& [offset, of] : spans)
    for (const Span& span : of)
      if (span.count >= kMinDirectionBonds &&
          span.count * kDirectionShare >= span.last - span.first) {
        const BondSlots::Direction d{offset, span.first, span.last, s.dense_slots};
        index.add(d);
        s.directions.push_back(d);
        s.dense_slots += span.last - span.first;
      }
  return index;
}
}  // namespace

BondSlots make_bond_slots(const BondTable& bonds) {
  BondSlots s;
  const std::size_t n = bonds.particle_count();
  s.particles = n;
  const DirectionIndex directions = choose_directions(bonds, s);

  // Owner entries first (i ascending, j ascending: the extra list comes out
  // sorted by owner, then partner), then each other entry finds its owner's.
  s.entry_slot.assign(bonds.entry_count(), 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      if (j < i) continue;
      if (const BondSlots::Direction* d = directions.find(j - i, i)) {
        s.entry_slot[b] = static_cast<std::uint32_t>(d->slot(i));
      } else {
        s.entry_slot[b] = static_cast<std::uint32_t>(s.dense_slots + s.extra_owner.size());
        s.extra_owner.push_back(static_cast<std::uint32_t>(i));
        s.extra_partner.push_back(static_cast<std::uint32_t>(j));
      }
    }
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      if (j > i) continue;
      if (const BondSlots::Direction* d = directions.find(i - j, j)) {
        s.entry_slot[b] = static_cast<std::uint32_t>(d->slot(j));
        continue;
      }
      std::size_t k =
          static_cast<std::size_t>(std::lower_bound(s.extra_owner.begin(), s.extra_owner.end(),
                                                    static_cast<std::uint32_t>(j)) -
                                   s.extra_owner.begin());
      while (s.extra_partner[k] != i) ++k;
      s.entry_slot[b] = static_cast<std::uint32_t>(s.dense_slots + k);
    }

  // Rows by their entries' offsets and slot shifts (slot - m, the same for
  // every particle m of a body's interior); the common ones whose entries
  // all have dense slots become patterns.
  using Row = std::vector<std::pair<std::ptrdiff_t, std::ptrdiff_t>>;
  std::vector<Row> rows(n);
  std::map<Row, std::size_t> row_count;
  for (std::size_t i = 0; i < n; ++i) {
    bool dense = true;
    const auto m = static_cast<std::ptrdiff_t>(i);
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto delta = static_cast<std::ptrdiff_t>(bonds.neighbor[b]) - m;
      dense = dense && s.entry_slot[b] < s.dense_slots;
      rows[i].emplace_back(delta, static_cast<std::ptrdiff_t>(s.entry_slot[b]) - m);
    }
    if (dense) ++row_count[rows[i]];
  }
  std::map<Row, std::int32_t> pattern_of;
  for (const auto& [row, count] : row_count) {
    if (count < kMinPatternParticles) continue;
    pattern_of[row] = static_cast<std::int32_t>(s.patterns.size());
    BondSlots::Pattern pattern;
    for (const auto& [delta, shift] : row) {
      pattern.slot_shift.push_back(shift);
      pattern.partner_shift.push_back(delta);
    }
    s.patterns.push_back(std::move(pattern));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = pattern_of.find(rows[i]);
    const std::int32_t id = p == pattern_of.end() ? -1 : p->second;
    if (!s.runs.empty() && s.runs.back().pattern == id)
      s.runs.back().end = i + 1;
    else
      s.runs.push_back({i, i + 1, id});
  }
  return s;
}

void fill_slot_array(const BondSlots& slots, const BondTable& bonds,
                     const std::vector<double>& per_entry, double* out) {
  for (std::size_t i = 0; i < slots.particles; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
      if (bonds.neighbor[b] > i) out[slots.entry_slot[b]] = per_entry[b];
}

std::vector<double> slot_values(const BondSlots& slots, const BondTable& bonds,
                                const std::vector<double>& per_entry) {
  std::vector<double> values(slots.slot_count(), 0.0);
  fill_slot_array(slots, bonds, per_entry, values.data());
  return values;
}

}  // namespace mpsolid
