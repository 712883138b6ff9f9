#pragma once
// Rankine-Hugoniot relations of a planar shock in an ideal gas: the state
// behind a shock of Mach number M running into a gas at rest, and the
// shock it reflects from a rigid wall (from the exact Riemann solution of
// the shocked gas against its mirror image).
#include "src/gas/exact_riemann.hpp"

namespace mpsolid {

// The state behind a shock of Mach number `mach` (> 1) running in +x into
// `ahead` (at rest), and the shock's speed.
struct ShockedGas {
  GasState1D behind;
  double shock_speed = 0;
};
ShockedGas shocked_gas(GasState1D ahead, double mach, double gamma);

// The gas at rest between a rigid wall and the shock that `behind` (moving
// toward the wall at +u) reflects, and that shock's speed away from the
// wall (positive).
struct ReflectedShock {
  GasState1D at_wall;
  double shock_speed = 0;
};
ReflectedShock reflected_shock(GasState1D behind, double gamma);

}  // namespace mpsolid
