#pragma once
// run.json: what ran, on what build, and how fast. A resumed run is a new
// segment: run.json describes the latest one at the top level and lists every
// segment (command line, steps, wall time per phase, frames, bytes,
// checkpoints) under "segments", oldest first.
#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stable_step_estimate.hpp"
#include "src/core/timers.hpp"

namespace mpsolid {

// JSON objects keep their members in the order written.
using Json = nlohmann::ordered_json;

// How a run (segment) ended. `interrupted` is what a checkpoint written
// mid-run records: a run that stopped there without a word was killed.
enum class Outcome { completed, interrupted, stopped_by_sigint, stopped_by_sigterm, unstable };

// The words run.json, checkpoints and the summary use ("stopped by SIGTERM").
const char* outcome_name(Outcome outcome);
bool stopped_by_signal(Outcome outcome);

struct RunFacts {
  std::string command_line;
  std::vector<std::string> overrides;  // --set values of this segment
  int threads = 1;
  int ranks = 1;  // MPI ranks (docs/mpi.md)
  // Per rank over several ranks (this segment).
  std::vector<RankTimes> rank_times;
  // Over several ranks, whether rank 0 held a copy of the particles and
  // bonds ("whole") or only the bodies, loads and probes ("none").
  bool rank_zero_copy = true;
  CutFacts cut;  // how the case is cut over the ranks
  // The threads stepping as ranks on one process (threads = 0: none did).
  ThreadCrossing thread_crossing;
  std::int64_t steps = 0;  // steps advanced in this run
  double wall_seconds = 0;
  int frames = 0;
  std::uintmax_t bytes_written = 0;
  Outcome outcome = Outcome::completed;
  std::string diagnosis;  // why an unstable run stopped, in words
  Json diagnosis_json;    // the same as a JSON object (null otherwise)
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::int64_t start_step = 0;          // where this run (segment) started
  int checkpoints = 0;                  // checkpoints written
  std::uintmax_t checkpoint_bytes = 0;  // their size
  double checkpoint_seconds = 0;        // wall time writing them (output snapshots included)
  double wait_at_start = 0;             // team_wait_seconds() when the segment started
  double thread_wait_seconds = 0;       // threads' time at barriers in this segment, summed
  // Wall seconds stepped at each team size, and how often the size changed
  // (src/app/thread_governor.hpp).
  std::vector<std::pair<int, double>> team_size_seconds;
  int team_size_changes = 0;
};

// What a report shows besides the facts: the case, the state reached, the
// phase timers and the automatic step's estimate.
struct RunReportInputs {
  const CaseSpec& spec;
  const SolverState& state;
  std::size_t particles, bonds;  // the run's (`state` may hold none of them)
  const PhaseTimers& timers;
  const StableStepEstimate& stable_step;
  // The gas's named arrays for a checkpoint (empty without a gas).
  std::vector<std::pair<std::string, std::vector<double>>> gas = {};
};

// One segment as a JSON object.
Json segment_json(const RunReportInputs& in, const RunFacts& facts);

// The whole run.json text; `previous_segments` are the segments before this
// one (from the checkpoint), each a JSON object's text.
std::string run_report_json(const RunReportInputs& in, const RunFacts& facts,
                            const std::vector<std::string>& previous_segments = {});

}  // namespace mpsolid
