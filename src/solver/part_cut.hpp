#pragma once
// How a case is cut over ranks (docs/mpi.md), made from the case alone (no
// rank holds the bond table): slabs of storage (decompose_case: each rank
// one contiguous range, which within a body is a slab of its fill's rows),
// bands across the case's longest extent (each rank the sites whose
// coordinate along that axis falls in its band: one piece of storage per
// row it crosses), or blocks (recursive coordinate bisection: the sites
// halved across the longest extent of their box, each half's ranks and box
// halved again, until each block is one rank's). A long body stored along
// its length is cut along its length by slabs and across it by bands; a
// square one at four ranks is cut into quarters by blocks. The cut chosen
// is the one whose halo, estimated from the sites within a bond's reach of
// each cut, is the smallest (a finer one only where it saves a fifth).
// Bodies under a force and rigid bodies small against a rank's share are
// kept whole by every cut (bodies_kept_whole); a larger rigid body falls
// where the cut puts it, split between ranks if need be.
#include <string>

#include "src/case/case_spec.hpp"
#include "src/distributed/decomposition.hpp"

namespace mpsolid {

enum class CutChoice { automatic, slabs, bands, blocks };

struct CaseCut {
  Decomposition decomposition;
  std::string kind;  // "slabs", "bands along x" (y, z), "blocks"
  // The ghosts each cut implies, estimated: the sites within a bond's reach
  // of each cut, over the cuts (0 with one rank).
  double slab_ghosts = 0, band_ghosts = 0, block_ghosts = 0;
};

// The cut of `spec` over `ranks`.
CaseCut cut_case(const CaseSpec& spec, int ranks, CutChoice choice = CutChoice::automatic);

}  // namespace mpsolid
