#pragma once
// Runs of consecutive particles whose bond rows fit one pattern: a list of
// (partner offset j - i, lattice shell) in ascending offset, of which each
// particle's row is the entries its mask names. A lattice body stored line
// by line has one pattern through its interior, and the rows of its
// boundary particles (fewer bonds, the same offsets) fit it with entries
// masked off, so the space gathers (kernels/paper_gather_model.hpp,
// kernels/gradient_gather_model.hpp) take kLanes particles at a time almost
// everywhere: each entry's partners are kLanes consecutive particles
// (unit-stride loads) and its shell constants one value. A masked entry is
// computed with whatever particle its offset lands on and its terms are then
// selected away, so a particle's sum runs over its own row in order: the
// bits of the row by row gather. Nothing per bond is stored.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif

#include "kernels/bond_slots.hpp"
#include "kernels/lanes.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"

namespace mpsolid {

struct RowPattern {
  std::vector<std::ptrdiff_t> partner_shift;  // j - i of each entry, ascending
  std::vector<std::uint8_t> shell;            // the lattice shell of each entry
};

struct RowPatterns {
  using Run = BondSlots::Run;
  static constexpr std::size_t kMaxEntries = 64;  // a mask's bits
  std::vector<RowPattern> patterns;
  std::vector<Run> runs;               // cover [0, particles) in order; pattern < 0: row by row
  std::vector<std::uint64_t> present;  // per particle: bit k set if entry k is in its row
};

// The patterns of a bond table, `shell_of_entry` naming each entry's shell
// (`off_shell`: none; such a row is on no run). The patterns are the rows
// that runs of at least kLanes particles share, then the unions of the rows
// of windows of at least kLanes consecutive particles (at most a row and a
// half wide); a particle left over joins the run before or after it if its
// row fits that run's pattern. Every offset of a run's pattern lands inside
// the table.
RowPatterns find_row_patterns(const BondTable& bonds,
                              const std::vector<std::uint8_t>& shell_of_entry,
                              std::uint8_t off_shell);

// Every particle row by row (the gathers' other path, for tests).
RowPatterns row_by_row(std::size_t particles);

// kLanes integers side by side (indices, masks), as Lanes' companions.
using LaneInts = std::int64_t __attribute__((vector_size(kLanes * sizeof(std::int64_t))));

// kLanes particles' masks from m.
inline LaneInts load_masks(const RowPatterns& rows, std::size_t m) {
  LaneInts v;
  std::memcpy(&v, &rows.present[m], sizeof v);
  return v;
}
// value where entry k is present, else 0 (exact: the sums skip it).
inline Lanes keep_present(LaneInts masks, std::size_t k, Lanes value) {
  return ((masks >> static_cast<std::int64_t>(k)) & 1) != 0 ? value : Lanes{};
}
// Whether every particle of the group has the pattern's whole row.
inline bool whole_rows(const RowPatterns& rows, const RowPattern& pattern, std::size_t m) {
  const std::size_t count = pattern.partner_shift.size();
  const std::uint64_t all = count == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << count) - 1;
  for (std::size_t k = 0; k < kLanes; ++k)
    if (rows.present[m + k] != all) return false;
  return true;
}

// One entry of a row: its partner (or the first of kLanes consecutive
// ones) and its shell.
struct RowEntry {
  std::size_t partner;
  std::uint8_t shell;
};
// The k-th entries of kLanes particles' own rows (partner and shell per
// lane; a lane whose row is shorter has its own index and shell 0 there).
struct LaneEntry {
  LaneInts partner;
  LaneInts shell;
};

// Values of `a` at a partner: one value (T double), kLanes consecutive ones
// (T Lanes, j an index) or kLanes anywhere (j LaneInts).
template <class T>
inline T load_at(const double* a, std::size_t j) {
  return load_as<T>(a + j);
}
template <class T>
inline Lanes load_at(const double* a, LaneInts j) {
#if defined(__AVX512F__)
  // The masked form: the plain one starts from an undefined register that
  // GCC 12 warns of.
  return reinterpret_cast<Lanes>(
      _mm512_mask_i64gather_pd(_mm512_setzero_pd(), 0xFF, reinterpret_cast<__m512i>(j), a, 8));
#else
  Lanes v;
  for (std::size_t k = 0; k < kLanes; ++k) v[k] = a[j[k]];
  return v;
#endif
}

// The lanes of a group that a call is the first to compute, [first, last):
// a kernel that writes its particles' outputs whole may write every lane
// (a particle done twice gets the same bits twice); one that adds to an
// output writes these only (store_fresh).
struct FreshLanes {
  std::size_t first = 0, last = kLanes;
};
inline void store_fresh(double* to, double v, FreshLanes) {
  *to = v;
}
inline void store_fresh(double* to, Lanes v, FreshLanes fresh) {
  if (fresh.first == 0 && fresh.last == kLanes) return store_lanes(to, v);
  for (std::size_t k = fresh.first; k < fresh.last; ++k) to[k] = v[k];
}

// A gather over the particles of `block`, each summing its row in order:
// pass(T{}, i, count, entry, keep, fresh) with
// - T = Lanes for kLanes particles from i along a run: entry(k) the
//   pattern's k-th (RowEntry), keep(k, v) v where entry k is in a
//   particle's row and 0 elsewhere;
// - T = Lanes for kLanes consecutive particles from i that no pattern fits
//   (or too few of them do):
//   entry(k) their rows' k-th (LaneEntry), keep(k, v) v where the row has a
//   k-th entry;
// - T = double for one particle (in a block of fewer than kLanes):
//   entry(k) its row's k-th, keep(k, v) = v.
// Shells from `shell_of_entry`; `fresh` the lanes no call before computed.
template <class Pass>
void gather_rows(const RowPatterns& rows, const BondTable& bonds,
                 const std::vector<std::uint8_t>& shell_of_entry, Range block, Pass&& pass) {
  const auto all = [](std::size_t, auto v) { return v; };
  const auto one_row = [&](std::size_t i) {
    const std::uint32_t first = bonds.begin(i);
    pass(
        0.0, i, bonds.end(i) - first,
        [&](std::size_t k) {
          const std::uint32_t b = first + static_cast<std::uint32_t>(k);
          return RowEntry{bonds.neighbor[b], shell_of_entry[b]};
        },
        all, FreshLanes{0, 1});
  };
  // kLanes consecutive particles from m, each over its own row.
  const auto own_rows = [&](std::size_t m, FreshLanes fresh) {
    LaneInts first, length;
    std::size_t count = 0;
    for (std::size_t l = 0; l < kLanes; ++l) {
      first[l] = bonds.begin(m + l);
      length[l] = bonds.end(m + l) - bonds.begin(m + l);
      count = std::max(count, static_cast<std::size_t>(length[l]));
    }
    const auto entry = [&](std::size_t k) {
      LaneEntry e;
      for (std::size_t l = 0; l < kLanes; ++l) {
        const bool has = static_cast<std::int64_t>(k) < length[l];
        const auto b = static_cast<std::size_t>(first[l]) + k;
        e.partner[l] = has ? bonds.neighbor[b] : static_cast<std::int64_t>(m + l);
        e.shell[l] = has ? shell_of_entry[b] : 0;
      }
      return e;
    };
    pass(
        Lanes{}, m, count, entry,
        [&](std::size_t k, Lanes v) { return static_cast<std::int64_t>(k) < length ? v : Lanes{}; },
        fresh);
  };
  // [begin, end) kLanes at a time, group(m, fresh), the groups reaching
  // past `end` (or back before `begin`) within the block where fewer are
  // left.
  const auto in_groups = [&](std::size_t begin, std::size_t end, auto&& group) {
    if (block.end - block.begin < kLanes) {
      for (std::size_t i = begin; i < end; ++i) one_row(i);
      return;
    }
    const std::size_t stop = std::min(block.end, std::max(end, begin + kLanes));
    for (std::size_t g = begin; g < end; g += kLanes) {
      const std::size_t m = std::min(g, stop - kLanes);
      group(m, FreshLanes{g - m, std::min(end, m + kLanes) - m});
    }
  };
  for_each_run(
      rows, block,
      [&](std::size_t begin, std::size_t end, const RowPattern& pattern) {
        if (end - begin < kLanes) return in_groups(begin, end, own_rows);
        const std::size_t count = pattern.partner_shift.size();
        in_groups(begin, end, [&](std::size_t m, FreshLanes fresh) {
          const auto entry = [&](std::size_t k) {
            return RowEntry{
                static_cast<std::size_t>(static_cast<std::ptrdiff_t>(m) + pattern.partner_shift[k]),
                pattern.shell[k]};
          };
          if (whole_rows(rows, pattern, m)) {
            pass(Lanes{}, m, count, entry, all, fresh);
          } else {
            const LaneInts masks = load_masks(rows, m);
            pass(
                Lanes{}, m, count, entry,
                [&](std::size_t k, Lanes v) { return keep_present(masks, k, v); }, fresh);
          }
        });
      },
      [&](std::size_t begin, std::size_t end) { in_groups(begin, end, own_rows); });
}

// gather_rows over `range`, in the team's blocks (src/core/parallel.hpp).
template <class Pass>
void gather_range(const RowPatterns& rows, const BondTable& bonds,
                  const std::vector<std::uint8_t>& shell_of_entry, Range range, Pass&& pass) {
  parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
    gather_rows(rows, bonds, shell_of_entry, {b, e}, pass);
  });
}

}  // namespace mpsolid
