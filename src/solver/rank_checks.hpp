#pragma once
// A stability check from the MPI ranks' shares (docs/mpi.md): what the check
// reads of the particles (the motion sums, the largest speed, the first
// non-finite particle, the loads' and drivers' work) computed by each rank
// on its own particles and combined on rank 0 with the bits of the whole
// state's, so that a check moves no rank's slice. Used where the check reads
// nothing else of the particles but contact's candidates (rank 0 keeps a
// copy of those: src/solver/contact_copy.hpp) and a pressure's nodes (each
// rank positions those it hosts): no gas.
#include <cstddef>
#include <vector>

#include "src/core/diagnostics.hpp"
#include "src/core/stability.hpp"
#include "src/distributed/decomposition.hpp"
#include "src/distributed/ordered_sum_parts.hpp"
#include "src/solver/distributed_step.hpp"

namespace mpsolid {

// What a check reads, from the whole state or from the ranks.
struct CheckFigures {
  Diagnostics diagnostics;  // the motion's, the strain energy, the external work
  StabilityVerdict finite;  // ok, or the first non-finite particle
  Fastest fastest;          // the first fastest moving particle
  IntegrityReport integrity;
  HistoryReadings readings;  // what a history row reads of the particles
  // With contact: the moving candidates' positions (x, y[, z] each, each
  // rank's own in candidate order, the ranks in rank order:
  // in_candidate_order puts them in candidate order) and the first step
  // any rank found a pair too close (-1: none).
  std::vector<double> candidate_positions;
  std::int64_t too_close = -1;
};

// A rank's share, appended to `out` (its owned particles, in global storage
// indices; its own loads' and rigid bodies' work and fields in their order;
// its part of the elastic bodies' extents, its probes, the pressure nodes it
// hosts and its moving contact candidates).
void append_rank_check(const RankPart& part, const RankGroup& world, std::vector<double>& out);

// Every rank's share read in rank order, then the figures.
class RankChecks {
 public:
  // For a run with `elastic_bodies` elastic bodies (their extents).
  explicit RankChecks(std::size_t elastic_bodies) : elastic_bodies_(elastic_bodies) {}
  // The share of the rank that owns `owned` (its storage ranges); its rigid
  // bodies' and loads' fields go into `global` (rank 0's copy).
  void read(const std::vector<double>& in, std::size_t& at, SolverState& global,
            const std::vector<Range>& owned);
  // The figures of the whole state `global` (its loads and rigid bodies as
  // set up: which rank owns which), cut by `d`; the strain energy and the
  // integrity check come from the fields round.
  CheckFigures finish(const SolverState& global, const Decomposition& d,
                      const RankFields& fields) const;

 private:
  std::vector<OrderedSumPart<kMotionSums>> motion_;
  std::vector<std::vector<double>> load_work_, body_work_;  // per rank, in its order (no pressure)
  std::vector<double> pressure_nodes_;  // (pressure, node, x, y, z) from every rank
  std::size_t elastic_bodies_;
  CheckFigures figures_;  // the first-found and largest, the extents, the probes
};

}  // namespace mpsolid
