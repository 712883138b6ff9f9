#pragma once
// What this build is: `mpsolid --version` and the Python module's version().
#include <string>

namespace mpsolid {

struct VersionFacts {
  std::string version, git_commit, compiler, build_type, cxx_flags;
  std::string openmp;  // "OpenMP 201511 (2 cores)" or "no OpenMP"
  std::string mpi;     // "Open MPI v4.1.4" or "none" (docs/mpi.md)
  int cores = 1;
};

VersionFacts version_facts();
// The --version text: every fact above in three lines.
std::string version_text();

}  // namespace mpsolid
