#pragma once
// A rank's rows of a frame or a checkpoint, written in place
// (src/distributed/placed_rows.hpp) into the file rank 0 laid out
// (src/core/frame_rows.hpp): each rank its own particles in id order, so no
// rank gathers another's. A frame's surface marks come from the rank's own
// particles: in space from their bonds (their partners' positions current
// after the fields round), in the plane from the surfaces' nodes, each rank
// computing the nodes its particles host and every rank receiving them all
// (their number grows with a body's perimeter, not its area).
#include <string>
#include <vector>

#include "src/core/frame_rows.hpp"
#include "src/distributed/rank_group.hpp"
#include "src/solver/distributed_step.hpp"

namespace mpsolid {

// A placement as one text, and back (for a broadcast).
std::string encode_placement(const RowPlacement& placement);
RowPlacement decode_placement(const std::string& text);

// Writes the part's owned particles' rows of `placement` (a frame's after
// the fields round), or reads them from a checkpoint into the part (a
// restore), and appends what rank 0 reads: the system's error number (0:
// done) and a checkpoint's arrays' hash terms. Every rank must call it (a
// plane frame's nodes are gathered).
void append_rank_rows(RankPart& part, const RankGroup& world,
                      const std::vector<FrameSurface>& surfaces, const RowPlacement& placement,
                      std::vector<double>& out);
// A compressed frame's rows of a rank's owned particles, chunk by chunk of
// ids (RowPlacement::Content::compressed_frame: offsets hold the particles
// and the ids per chunk), every dataset's rows of a chunk's ids in one
// message of doubles (every element type fits one exactly). Rank 0 holds
// one chunk at a time, never the ranks' whole rows.
class FrameChunks {
 public:
  // Every rank must make it at once (a plane frame's nodes are gathered).
  FrameChunks(const RankPart& part, const RankGroup& world,
              const std::vector<FrameSurface>& surfaces, const RowPlacement& placement);
  std::size_t chunks() const { return chunks_; }
  // This rank's rows of chunk c (perhaps none), dataset after dataset.
  std::vector<double> rows(std::size_t c) const;

 private:
  const ParticleStore& particles_;
  SurfaceMarks marks_;
  std::vector<std::size_t> members_;  // owned storage indices by ascending id
  std::uint64_t total_ = 0, per_chunk_ = 0;
  std::size_t chunks_ = 0;
};
// Rank 0's chunk of a compressed frame, assembled from every rank's rows.
class ChunkRows {
 public:
  ChunkRows(int dimension, std::uint64_t first, std::size_t count);
  // A rank's rows of the chunk (FrameChunks::rows).
  void add(const std::vector<double>& rows);
  const std::vector<RowValues>& values() const { return values_; }

 private:
  const std::vector<RowLayout>& layout_;
  std::uint64_t first_;
  std::vector<RowValues> values_;
};

// Adds rank `rank`'s report (as append_rank_rows wrote it) to `total`;
// returns, when it could not write (or read), what failed (the file, the rank, the
// system's reason), else "". Rank 0 reads every rank's report before it
// reports a failure, so that no rank waits on it.
std::string read_rank_rows(const std::vector<double>& in, std::size_t& at, int rank,
                           const RowPlacement& placement, PlacedRows& total);

}  // namespace mpsolid
