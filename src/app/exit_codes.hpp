#pragma once
// The process's exit codes (README: exit codes).

namespace mpsolid {

// kExitStopped: a stop signal (SIGINT, SIGTERM) ended the run after writing a
// checkpoint and the outputs; `mpsolid resume` continues it.
enum ExitCode : int {
  kExitOk = 0,
  kExitError = 1,
  kExitBadInput = 2,
  kExitUnstable = 3,
  kExitStopped = 4
};

}  // namespace mpsolid
