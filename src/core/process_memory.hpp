#pragma once
// The process's peak resident memory (Linux getrusage: ru_maxrss in KiB),
// for the memory each MPI rank reports in run.json.
#include <sys/resource.h>

namespace mpsolid {

inline double peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return 1024.0 * static_cast<double>(usage.ru_maxrss);
}

}  // namespace mpsolid
