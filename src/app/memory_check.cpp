#include "src/app/memory_check.hpp"

#include <fmt/format.h>

#include <fstream>
#include <string>

#include "src/core/types.hpp"

namespace mpsolid {

std::uint64_t available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  std::uint64_t kib = 0;
  std::string unit;
  while (in >> key >> kib >> unit)
    if (key == "MemAvailable:") return kib * 1024;
  return 0;
}

void check_memory(const CaseSpec& spec, int threads, std::uint64_t available, double share) {
  if (available == 0) return;
  const double particles = share * static_cast<double>(spec.particle_count());
  const bool space = spec.dimension == 3;
  const double per_particle =
      (space ? kBytesPerParticleInSpace : kBytesPerParticle) +
      (threads > 1 ? (space ? kPartBytesPerParticleInSpace : kPartBytesPerParticle) : 0.0);
  const double needed = particles * per_particle;
  if (needed <= static_cast<double>(available)) return;
  const double gib = 1024.0 * 1024.0 * 1024.0;
  throw InputError(fmt::format(
      "{}: {:.3g} particles (l0 = {} m{}) need about {:.3g} GiB at {} thread(s) ({} bytes per "
      "particle, bonds included{}); this machine has {:.3g} GiB available: use a larger l0 "
      "(memory goes as 1 / l0^{}){} or {}",
      spec.source, particles, spec.l0,
      share < 1 ? fmt::format(", {:.3g} of the case: this machine's ranks' share", share) : "",
      needed / gib, threads, per_particle, threads > 1 ? ", the threads' parts too" : "",
      static_cast<double>(available) / gib, spec.dimension, threads > 1 ? ", --threads 1" : "",
      share < 1 ? "more machines" : "a machine with more memory"));
}

}  // namespace mpsolid
