#pragma once
// A parsed command started: MPI under an MPI launcher (rank 0 runs the
// command, the other ranks follow it: src/solver/ranked_stepper.hpp), the
// launches refused or noted (a build without MPI started as several ranks,
// srun without its MPI plugin, a study over ranks), the thread count, and
// every error of the command as its exit code (src/app/run.hpp).
#include "src/app/command_line.hpp"

namespace mpsolid {

// Runs the command; returns the process's exit code. `argc` and `argv` go to
// MPI's start.
int launch(const CommandLine& command_line, int* argc, char*** argv);

}  // namespace mpsolid
