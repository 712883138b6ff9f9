#pragma once
// The files of a run folder and how they stay consistent with checkpoint.h5.
//
// history.csv and frames.h5 are written to staging files (NAME.tmp), flushed
// at every frame. A checkpoint first publishes copies of both under their
// names (and frames.xdmf), then replaces checkpoint.h5 (temporary file,
// fsync, rename), which records how many frames and history bytes belong to
// its step. So the published files always hold at least what the checkpoint
// records, whatever moment a process is killed at, and a resumed run
// continues them from exactly that point: no frame lost or written twice.
// A fresh run first removes an old checkpoint.h5, so a checkpoint never
// refers to another run's files; a random run id written into both checks it.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "src/io/checkpoint.hpp"
#include "src/io/frame_writer.hpp"
#include "src/io/history_writer.hpp"
#include "src/io/run_report.hpp"

namespace mpsolid {

// After a run failed writing its outputs (the RunFolder destroyed): removes
// every temporary file it may have left in `dir` and returns what the user
// must know: the failure, "no space left" when the file system is full, and
// which checkpoint (and the outputs it records) is intact to resume from.
std::string abandon_failed_run(const std::filesystem::path& dir, const std::string& failure);

// The results of an earlier run in `dir` (history.csv, frames.h5,
// checkpoint.h5, run.json: those present), in words for a refusal; empty if
// there are none.
std::string earlier_results(const std::filesystem::path& dir);

// Whether `dir`'s run.json records the run completed at checkpoint `last`'s
// step, every segment `last` lists included: false for a run killed after its
// last checkpoint but before run.json was written.
bool run_report_completes(const std::filesystem::path& dir, const Checkpoint& last);

class RunFolder {
 public:
  // A fresh run in `dir` (created if needed).
  // `particles` and `bond_hash` (BondTable::hash) are the run's: over MPI
  // ranks `state` may hold no particle.
  RunFolder(const std::filesystem::path& dir, const SolverState& state, const CaseSpec& spec,
            std::size_t particles, std::uint64_t bond_hash);
  // A resumed run: `state` is the restored state of `from`.
  RunFolder(const std::filesystem::path& dir, const SolverState& state, const CaseSpec& spec,
            const Checkpoint& from);

  // A history.csv row (once per step; the particles' readings given, or
  // read from `state`), and a frame with its row.
  void write_history(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                     const HistoryReadings* readings = nullptr);
  void write_frame(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                   const GasFrame& gas = {});
  // A frame whose particles' rows `placer` writes in place (over MPI ranks,
  // every rank its own), with its history row (`state`: rank 0's copy, its
  // particles' readings given or read from it).
  void write_placed_frame(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                          const HistoryReadings* readings, const GasFrame& gas,
                          const RowPlacer& placer);
  // Publishes copies of the outputs (unless published), then writes
  // checkpoint.h5 with the run.json segments so far, this one described by
  // `facts` (its figures are brought up to date here). With `placer`, the
  // particle arrays are written in place by it and `in.state`'s particles
  // are not read.
  void checkpoint(const RunReportInputs& in, RunFacts facts, const RowPlacer& placer = {});
  // Renames the staging files to their names (end of the run).
  void publish();
  // Brings the output figures of `facts` up to date.
  void fill(RunFacts& facts) const;

  const std::vector<std::string>& previous_segments() const { return previous_segments_; }
  std::int64_t last_checkpoint_step() const { return last_checkpoint_step_; }
  std::int64_t last_frame_step() const { return last_frame_step_; }
  static std::filesystem::path checkpoint_path(const std::filesystem::path& dir) {
    return dir / "checkpoint.h5";
  }

 private:
  std::filesystem::path dir_;
  std::uint64_t run_id_ = 0;
  std::uint64_t bond_hash_ = 0;
  HistoryWriter history_;
  FrameWriter frames_;
  std::vector<std::string> previous_segments_;
  bool published_ = false;
  std::int64_t last_checkpoint_step_ = -1;
  std::int64_t last_frame_step_ = -1;
  std::int64_t last_history_step_ = -1;
  int checkpoints_ = 0;
  std::uintmax_t checkpoint_bytes_ = 0;
  double checkpoint_seconds_ = 0;
};

}  // namespace mpsolid
