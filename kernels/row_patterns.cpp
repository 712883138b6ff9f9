#include "kernels/row_patterns.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <utility>

namespace mpsolid {

namespace {
using Row = std::vector<std::pair<std::ptrdiff_t, std::uint8_t>>;

// Particle i's row as (offset, shell) pairs, read from the table when asked
// (the rows of millions of particles are not kept).
class TableRows {
 public:
  TableRows(const BondTable& bonds, const std::vector<std::uint8_t>& shells)
      : bonds_(bonds), shells_(shells) {}
  const Row& of(std::size_t i) {
    fill(i, row_);
    return row_;
  }
  void fill(std::size_t i, Row& out) const {
    out.clear();
    for (std::uint32_t b = bonds_.begin(i); b < bonds_.end(i); ++b)
      out.emplace_back(
          static_cast<std::ptrdiff_t>(bonds_.neighbor[b]) - static_cast<std::ptrdiff_t>(i),
          shells_[b]);
  }
  bool same(std::size_t i, std::size_t j) const {
    const std::uint32_t length = bonds_.end(i) - bonds_.begin(i);
    if (bonds_.end(j) - bonds_.begin(j) != length) return false;
    for (std::uint32_t k = 0; k < length; ++k) {
      const std::uint32_t a = bonds_.begin(i) + k, b = bonds_.begin(j) + k;
      if (bonds_.neighbor[a] - i != bonds_.neighbor[b] - j || shells_[a] != shells_[b])
        return false;
    }
    return true;
  }

 private:
  const BondTable& bonds_;
  const std::vector<std::uint8_t>& shells_;
  Row row_;
};

// The mask of `row` within `pattern`, if the row fits it (every entry in it,
// in order) and every offset of the pattern from i lands in [0, n).
bool fit(const Row& row, const RowPattern& pattern, std::size_t i, std::size_t n,
         std::uint64_t& mask) {
  const auto at = static_cast<std::ptrdiff_t>(i);
  if (at + pattern.partner_shift.front() < 0 ||
      at + pattern.partner_shift.back() >= static_cast<std::ptrdiff_t>(n))
    return false;
  mask = 0;
  std::size_t k = 0;
  for (const auto& [shift, shell] : row) {
    while (k < pattern.partner_shift.size() && pattern.partner_shift[k] < shift) ++k;
    if (k == pattern.partner_shift.size() || pattern.partner_shift[k] != shift ||
        pattern.shell[k] != shell)
      return false;
    mask |= std::uint64_t{1} << k;
  }
  return true;
}
}  // namespace

RowPatterns find_row_patterns(const BondTable& bonds,
                              const std::vector<std::uint8_t>& shell_of_entry,
                              std::uint8_t off_shell) {
  const std::size_t n = bonds.particle_count();
  TableRows rows(bonds, shell_of_entry);
  std::vector<bool> usable(n, true);
  std::map<Row, std::size_t> row_count;
  std::size_t longest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t length = bonds.end(i) - bonds.begin(i);
    longest = std::max(longest, length);
    usable[i] = length > 0 && length <= RowPatterns::kMaxEntries;
    // A pattern lists its offsets ascending: a row whose partners are not
    // (a rank's part in pieces, its ghosts stored after its own particles)
    // goes row by row.
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
      usable[i] = usable[i] && shell_of_entry[b] != off_shell &&
                  (b == bonds.begin(i) || bonds.neighbor[b] > bonds.neighbor[b - 1]);
    if (usable[i]) ++row_count[rows.of(i)];
  }
  RowPatterns s;
  std::map<Row, std::int32_t> pattern_of;
  for (const auto& [row, count] : row_count) {
    if (count < kLanes) continue;
    pattern_of[row] = static_cast<std::int32_t>(s.patterns.size());
    RowPattern pattern;
    for (const auto& [shift, shell] : row) {
      pattern.partner_shift.push_back(shift);
      pattern.shell.push_back(shell);
    }
    s.patterns.push_back(std::move(pattern));
  }

  // Each particle's own pattern where it lies in a run of at least kLanes
  // of them.
  std::vector<std::int32_t> assigned(n, -1);
  s.present.assign(n, 0);
  for (std::size_t i = 0; i < n;) {
    const auto own = usable[i] ? pattern_of.find(rows.of(i)) : pattern_of.end();
    std::size_t end = i + 1;
    if (own != pattern_of.end()) {
      while (end < n && usable[end] && rows.same(end, i)) ++end;
      if (end - i >= kLanes)
        for (std::size_t k = i; k < end; ++k) {
          assigned[k] = own->second;
          fit(rows.of(k), s.patterns[static_cast<std::size_t>(own->second)], k, n, s.present[k]);
        }
    }
    i = end;
  }
  // The rest in windows of consecutive particles whose rows' union is a
  // pattern they all fit (a thin plate's lines, the ends of a body's
  // lines), as long as the union stays within a row and a half.
  const std::size_t widest = std::min(RowPatterns::kMaxEntries, longest + longest / 2);
  for (std::size_t i = 0; i < n;) {
    if (assigned[i] >= 0 || !usable[i]) {
      ++i;
      continue;
    }
    Row all = rows.of(i), wider;
    std::size_t end = i + 1;
    for (; end < n && assigned[end] < 0 && usable[end]; ++end) {
      const Row& next = rows.of(end);
      wider.clear();
      std::set_union(all.begin(), all.end(), next.begin(), next.end(), std::back_inserter(wider));
      bool fits = wider.size() <= widest;
      for (std::size_t k = 1; fits && k < wider.size(); ++k)
        fits = wider[k].first != wider[k - 1].first;  // one shell per offset
      const auto reaches = [&](std::size_t at) {
        const auto a = static_cast<std::ptrdiff_t>(at);
        return a + wider.front().first >= 0 &&
               a + wider.back().first < static_cast<std::ptrdiff_t>(n);
      };
      if (!fits || !reaches(i) || !reaches(end)) break;
      std::swap(all, wider);
    }
    if (end - i < kLanes) {
      ++i;
      continue;
    }
    auto [at, added] = pattern_of.emplace(all, static_cast<std::int32_t>(s.patterns.size()));
    if (added) {
      RowPattern pattern;
      for (const auto& [shift, shell] : all) {
        pattern.partner_shift.push_back(shift);
        pattern.shell.push_back(shell);
      }
      s.patterns.push_back(std::move(pattern));
    }
    for (std::size_t k = i; k < end; ++k) {
      assigned[k] = at->second;
      fit(rows.of(k), s.patterns[static_cast<std::size_t>(at->second)], k, n, s.present[k]);
    }
    i = end;
  }
  // The others left join the run before them, or else after them.
  const auto join = [&](std::size_t i, std::size_t from) {
    if (assigned[i] >= 0 || assigned[from] < 0 || !usable[i]) return;
    if (fit(rows.of(i), s.patterns[static_cast<std::size_t>(assigned[from])], i, n, s.present[i]))
      assigned[i] = assigned[from];
  };
  for (std::size_t i = 1; i < n; ++i) join(i, i - 1);
  for (std::size_t i = n; i-- > 1;) join(i - 1, i);
  for (std::size_t i = 0; i < n; ++i) {
    if (!s.runs.empty() && s.runs.back().pattern == assigned[i])
      s.runs.back().end = i + 1;
    else
      s.runs.push_back({i, i + 1, assigned[i]});
  }
  return s;
}

RowPatterns row_by_row(std::size_t particles) {
  RowPatterns s;
  s.present.assign(particles, 0);
  if (particles > 0) s.runs.push_back({0, particles, -1});
  return s;
}

}  // namespace mpsolid
