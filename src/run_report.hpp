#pragma once
// run.json: what ran, on what build, and how fast.
#include <cstdint>
#include <string>

#include "src/simulation.hpp"

namespace mpsolid {

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
};

std::string run_report_json(const Simulation& sim, const RunFacts& facts);

}  // namespace mpsolid
