#include "kernels/bond_slots.hpp"

#include <map>
#include <utility>

namespace mpsolid {

namespace {
constexpr std::size_t kMinPatternParticles = 16;
constexpr std::size_t kDirectionShare = 8;  // a direction serves at least n / 8 bonds
}  // namespace

BondSlots make_bond_slots(const BondTable& bonds) {
  BondSlots s;
  const std::size_t n = bonds.particle_count();
  s.particles = n;

  std::map<std::size_t, std::size_t> offset_count;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
      if (bonds.neighbor[b] > i) ++offset_count[bonds.neighbor[b] - i];
  std::map<std::size_t, std::size_t> direction_of;
  for (const auto& [offset, count] : offset_count)
    if (count * kDirectionShare >= n) {
      direction_of[offset] = s.directions.size();
      s.directions.push_back(offset);
    }
  s.dense_slots = s.directions.size() * n;

  // Owner entries first (i ascending, j ascending: the extra list comes out
  // sorted by owner, then partner), then each other entry finds its owner's.
  s.entry_slot.assign(bonds.entry_count(), 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      if (j < i) continue;
      const auto d = direction_of.find(j - i);
      if (d != direction_of.end()) {
        s.entry_slot[b] = static_cast<std::uint32_t>(d->second * n + i);
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
      const auto d = direction_of.find(i - j);
      if (d != direction_of.end()) {
        s.entry_slot[b] = static_cast<std::uint32_t>(d->second * n + j);
        continue;
      }
      std::size_t k =
          static_cast<std::size_t>(std::lower_bound(s.extra_owner.begin(), s.extra_owner.end(),
                                                    static_cast<std::uint32_t>(j)) -
                                   s.extra_owner.begin());
      while (s.extra_partner[k] != i) ++k;
      s.entry_slot[b] = static_cast<std::uint32_t>(s.dense_slots + k);
    }

  // Rows by their offsets; the common ones whose offsets all have dense
  // arrays become patterns.
  std::vector<std::vector<std::ptrdiff_t>> row_offsets(n);
  std::map<std::vector<std::ptrdiff_t>, std::size_t> row_count;
  for (std::size_t i = 0; i < n; ++i) {
    bool dense = true;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto delta =
          static_cast<std::ptrdiff_t>(bonds.neighbor[b]) - static_cast<std::ptrdiff_t>(i);
      dense = dense && direction_of.count(static_cast<std::size_t>(delta > 0 ? delta : -delta));
      row_offsets[i].push_back(delta);
    }
    if (dense) ++row_count[row_offsets[i]];
  }
  std::map<std::vector<std::ptrdiff_t>, std::int32_t> pattern_of;
  for (const auto& [offsets, count] : row_count) {
    if (count < kMinPatternParticles) continue;
    pattern_of[offsets] = static_cast<std::int32_t>(s.patterns.size());
    BondSlots::Pattern pattern;
    for (const std::ptrdiff_t delta : offsets) {
      const auto d = static_cast<std::ptrdiff_t>(
          direction_of[static_cast<std::size_t>(delta > 0 ? delta : -delta)]);
      const auto base = d * static_cast<std::ptrdiff_t>(n);
      pattern.slot_shift.push_back(delta > 0 ? base : base + delta);
      pattern.partner_shift.push_back(delta);
    }
    s.patterns.push_back(std::move(pattern));
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = pattern_of.find(row_offsets[i]);
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
