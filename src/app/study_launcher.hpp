#pragma once
// `mpsolid study ...`: the study runner is the Python package's
// (python/mpsolid/study.py: a job pool, tables and plots), one implementation
// for the command line and for Python. This replaces the process with it.
#include <string>
#include <vector>

namespace mpsolid {

// Runs `python3 -m mpsolid study ARGS...` with the package this executable
// was built (or installed) with, and this executable for the study's runs.
// Returns only when it cannot start it (exit code 1, the reason on stderr).
int launch_study(const std::vector<std::string>& args);

}  // namespace mpsolid
