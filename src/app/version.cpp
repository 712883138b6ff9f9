#include "src/app/version.hpp"

#include <fmt/format.h>

#include "build_info.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/communicator.hpp"

namespace mpsolid {

VersionFacts version_facts() {
  VersionFacts f{build_info::version,
                 build_info::git_commit,
                 build_info::compiler,
                 build_info::build_type,
                 build_info::cxx_flags,
                 "",
                 "",
                 available_cores()};
  f.mpi = mpi_library_version();
#ifdef _OPENMP
  f.openmp = fmt::format("OpenMP {} ({} cores)", _OPENMP, f.cores);
#else
  f.openmp = "no OpenMP";
#endif
  return f;
}

std::string version_text() {
  const VersionFacts f = version_facts();
  const std::string mpi = f.mpi == "none" ? std::string("MPI: not in this build")
                                          : "MPI: " + f.mpi + " (every model over ranks)";
  return fmt::format("mpsolid {} (git {})\n  {}, {} build, flags {}\n  {}; {}", f.version,
                     f.git_commit, f.compiler, f.build_type, f.cxx_flags, f.openmp, mpi);
}

}  // namespace mpsolid
