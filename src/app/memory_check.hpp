#pragma once
// Refusing a case too large for the machine before anything is allocated:
// an estimate from the particle count against the memory the kernel says is
// available, so a user gets numbers instead of std::bad_alloc.
#include <cstdint>

#include "src/case/case_spec.hpp"

namespace mpsolid {

// Peak bytes per particle, bonds included: measured 1,434 B marginal (paper
// model, 0.28 to 1.13 M particles, bench/memory_rod.py; its bond slots hold
// 12 arrays of about 6.4 slots per particle), with some room.
inline constexpr double kBytesPerParticle = 1650;
// With several threads, each thread's part besides the whole state: its
// particles and ghosts, their bonds and its model (src/solver/thread_parts.hpp);
// measured 1,315 B marginal at 2 threads (bench/memory_rod.py --threads 2).
inline constexpr double kPartBytesPerParticle = 1500;
// The same in space (cubic lattice, 32 bond entries per interior particle):
// measured 1,970 B marginal with finite_strain and 1,577 B with paper at 1
// thread, and 1,267 B more for the parts at 2 threads (a rubber cube, 0.125
// to 0.26 M particles, peak resident memory of `mpsolid run`), with some room.
inline constexpr double kBytesPerParticleInSpace = 2300;
inline constexpr double kPartBytesPerParticleInSpace = 1500;

// MemAvailable of /proc/meminfo in bytes, or 0 when it cannot be read.
std::uint64_t available_memory_bytes();

// Throws InputError when the case's estimate at `threads` threads exceeds
// `available` bytes (a 0 `available` skips the check). `share`: the part
// of the case this machine holds (over MPI ranks with no whole copy on
// rank 0, its ranks' share of all the ranks).
void check_memory(const CaseSpec& spec, int threads, std::uint64_t available, double share = 1.0);

}  // namespace mpsolid
