#pragma once
// The command line, parsed: one struct per subcommand, the options that
// `run` and `resume` share written once.
//   mpsolid run CASE [--out DIR] [--force] [--threads N] [--fixed-threads] [--set KEY=VALUE]...
//   mpsolid resume DIR [--threads N] [--fixed-threads] [--set time.end=VALUE]...
//   mpsolid study CASE --vary KEY=V1,V2,... [...]   (python/mpsolid/study.py)
#include <string>
#include <variant>
#include <vector>

#include "src/solver/part_cut.hpp"

namespace mpsolid {

// What `run` and `resume` share: how the run steps, and the case overrides.
struct SteppingOptions {
  int threads = 0;  // 0: OMP_NUM_THREADS if set, else every core
  bool fixed_threads = false;
  std::vector<std::string> overrides;    // --set KEY=VALUE
  CutChoice cut = CutChoice::automatic;  // --cut: how several MPI ranks cut the case
};

struct RunCommand {
  std::string case_path;
  std::string out_dir;  // empty: out/<case name>[-hash of the --set values]
  bool force = false;
  SteppingOptions stepping;
};

struct ResumeCommand {
  std::string dir;
  SteppingOptions stepping;
};

struct StudyCommand {
  std::vector<std::string> arguments;  // every one goes to the Python study
};

struct CommandLine {
  std::variant<RunCommand, ResumeCommand, StudyCommand> command;
  std::string text;  // the whole command line, for run.json
};

// The parsed command line, or the exit code to leave with at once: after
// --help or --version (0), or a wrong command line (2, the error printed).
std::variant<CommandLine, int> parse_command_line(int argc, char** argv);

}  // namespace mpsolid
