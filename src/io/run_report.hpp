#pragma once
// run.json: what ran, on what build, and how fast. A resumed run is a new
// segment: run.json describes the latest one at the top level and lists every
// segment (command line, steps, wall time per phase, frames, bytes,
// checkpoints) under "segments", oldest first.
#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "src/solver/simulation.hpp"

namespace mpsolid {

// s as a JSON string literal, quotes and control characters escaped.
std::string json_quoted(const std::string& s);

struct RunFacts {
  std::string command_line;
  int threads = 1;
  std::int64_t steps = 0;  // steps advanced in this run
  double wall_seconds = 0;
  int frames = 0;
  std::uintmax_t bytes_written = 0;
  std::string outcome = "completed";
  std::string diagnosis;       // why an unstable run stopped, in words
  std::string diagnosis_json;  // the same as a JSON object
  std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
  std::int64_t start_step = 0;          // where this run (segment) started
  int checkpoints = 0;                  // checkpoints written
  std::uintmax_t checkpoint_bytes = 0;  // their size
  double checkpoint_seconds = 0;        // wall time writing them (output snapshots included)
};

// One segment as a JSON object (one line).
std::string segment_json(const Simulation& sim, const RunFacts& facts);

// `previous_segments`: the segments before this one (from the checkpoint).
std::string run_report_json(const Simulation& sim, const RunFacts& facts,
                            const std::vector<std::string>& previous_segments = {});

}  // namespace mpsolid
