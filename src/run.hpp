#pragma once
// The simulation loop with outputs: frames on the integer-step cadence,
// history.csv, frames.h5, case.resolved.toml and run.json, progress on a
// terminal and a closing summary.
#include <filesystem>
#include <string>

#include "src/case_spec.hpp"

namespace mpsolid {

struct RunOptions {
  std::filesystem::path out_dir;
  int threads = 1;
  bool progress = false;
  std::string command_line;
};

enum ExitCode : int { kExitOk = 0, kExitError = 1, kExitBadInput = 2, kExitUnstable = 3 };

// Runs the case to its end; returns the process exit code.
int run_case(const CaseSpec& spec, const RunOptions& options);

}  // namespace mpsolid
