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

void check_memory(const CaseSpec& spec, std::uint64_t available) {
  if (available == 0) return;
  const double particles = static_cast<double>(spec.particle_count());
  const double needed = particles * kBytesPerParticle;
  if (needed <= static_cast<double>(available)) return;
  const double gib = 1024.0 * 1024.0 * 1024.0;
  throw InputError(fmt::format(
      "{}: {:.3g} particles (l0 = {} m) need about {:.3g} GiB ({} bytes per particle, bonds "
      "included); this machine has {:.3g} GiB available: use a larger l0 (memory goes as "
      "1 / l0^2) or a machine with more memory",
      spec.source, particles, spec.l0, needed / gib, kBytesPerParticle,
      static_cast<double>(available) / gib));
}

}  // namespace mpsolid
