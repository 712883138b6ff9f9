#pragma once
// The simulation loop with outputs: frames on the integer-step cadence,
// history.csv, frames.h5, case.resolved.toml and run.json, progress on a
// terminal and a closing summary.
#include <filesystem>
#include <string>
#include <vector>

#include "src/app/exit_codes.hpp"
#include "src/case/case_spec.hpp"

namespace mpsolid {

class Followers;

struct RunOptions {
  std::filesystem::path out_dir;
  int threads = 1;
  bool progress = false;
  bool force = false;            // replace an earlier run's results in out_dir
  bool adaptive_threads = true;  // fewer threads when waiting makes them slower (thread_governor)
  std::string command_line;
  std::vector<std::string> overrides;  // the --set values, for run.json
  Followers* followers = nullptr;      // rank 0 of several MPI ranks: the run steps over them
};

// out/<case name>, with a short hash of the overrides when there are any, so
// runs of one case with different --set land in different folders.
std::filesystem::path default_out_dir(const std::string& case_name,
                                      const std::vector<std::string>& overrides);

// Runs the case to its end (or a stop signal, or a blow-up) in options.out_dir;
// returns the process exit code.
int run_case(const CaseSpec& spec, const RunOptions& options);

// Continues the run in options.out_dir from its checkpoint.h5, to the stored
// case's end or a later time.end given in `overrides` (only time.end,
// output.checkpoint_interval and output.compression may change). Throws
// InputError, before anything is written, for a missing, damaged or foreign
// checkpoint or outputs that do not match it.
int resume_run(const std::vector<std::string>& overrides, const RunOptions& options);

}  // namespace mpsolid
