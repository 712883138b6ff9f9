#pragma once
// What the outputs record of the whole bond table (its bond count and its
// hash, BondTable::hash, which a checkpoint keeps to refuse a resume with
// another table) from the ranks' parts, where no rank holds the table: each
// rank's owned rows are whole and in global order, so the ranks hash the
// pieces of the cut one after the other in storage order, array by array,
// each going on from the previous piece's value: the whole table's bits.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/rank_group.hpp"

namespace mpsolid {

struct BondTableFacts {
  std::size_t count = 0;   // bonds, each once
  std::uint64_t hash = 0;  // BondTable::hash of the whole table

  // As doubles for a message (the hash as two exact halves), and back.
  void append_to(std::vector<double>& out) const;
  static BondTableFacts read(const std::vector<double>& in, std::size_t& at);
};

// Collective over `world`: every rank gets the facts of the whole table
// from its part's table `local` (owned rows whole) and layout.
BondTableFacts bond_table_facts(const BondTable& local, const LocalLayout& layout,
                                const RankGroup& world);

}  // namespace mpsolid
