#pragma once
// Subnormal numbers flushed to zero while the solver computes (opt-in, the
// case key numerics.flush_subnormals).
//
// Ahead of a wave front the explicit scheme leaves displacements, velocities
// and forces that decay geometrically with distance; far from the front they
// fall below 2.2e-308, where arithmetic on subnormals is many times slower
// than on normal numbers (a microcode assist on x86). Flushing them (FTZ) and reading them as zero
// (DAZ) makes the paper model's steps on a 1 mm rod at rest up to 1.65x
// faster and a 0.5 mm rod's first 5,000 steps 1.42x (docs/performance.md);
// once the wave has crossed the rod it changes nothing. Positions and
// energies come out the same bits in the runs checked
// (tests/unit/test_float_mode.cpp), but the far field's velocities, forces
// and angles differ (below 1e-270), so it is not the default: the reference
// arithmetic is IEEE.
//
// The mode is per thread: parallel.cpp enters it on every thread of every
// parallel region and on the calling thread, and restores the previous mode
// when the region ends, so code outside the solver keeps IEEE arithmetic.
namespace mpsolid {

// Whether the solver's parallel regions flush subnormals (default false).
// Process-wide: a Simulation sets it from its case before it computes.
void set_flush_subnormals(bool flush);
bool flush_subnormals();

// Enters the chosen mode on this thread for its lifetime, then restores the
// thread's previous mode.
class SubnormalModeScope {
 public:
  SubnormalModeScope();
  ~SubnormalModeScope();
  SubnormalModeScope(const SubnormalModeScope&) = delete;
  SubnormalModeScope& operator=(const SubnormalModeScope&) = delete;

 private:
  unsigned long saved_;
};

}  // namespace mpsolid
