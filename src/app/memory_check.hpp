#pragma once
// Refusing a case too large for the machine before anything is allocated:
// an estimate from the particle count against the memory the kernel says is
// available, so a user gets numbers instead of std::bad_alloc.
#include <cstdint>

#include "src/case/case_spec.hpp"

namespace mpsolid {

// Peak bytes per particle, bonds included: measured 731 B (paper model, 1.1 M
// particles, docs/peer_comparison.md), with room for the corrected-gradient
// models' per-particle tensors and per-bond arrays.
inline constexpr double kBytesPerParticle = 900;

// MemAvailable of /proc/meminfo in bytes, or 0 when it cannot be read.
std::uint64_t available_memory_bytes();

// Throws InputError when the case's estimate exceeds `available` bytes (a 0
// `available` skips the check).
void check_memory(const CaseSpec& spec, std::uint64_t available);

}  // namespace mpsolid
