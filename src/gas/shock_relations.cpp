#include "src/gas/shock_relations.hpp"

#include <cmath>
#include <stdexcept>

namespace mpsolid {

ShockedGas shocked_gas(GasState1D ahead, double mach, double gamma) {
  if (!(mach > 1)) throw std::invalid_argument("a shock's Mach number must be above 1");
  const double m2 = mach * mach;
  const double c = std::sqrt(gamma * ahead.p / ahead.rho);
  ShockedGas s;
  s.shock_speed = ahead.u + mach * c;
  s.behind.p = ahead.p * (1 + 2 * gamma / (gamma + 1) * (m2 - 1));
  s.behind.rho = ahead.rho * (gamma + 1) * m2 / ((gamma - 1) * m2 + 2);
  s.behind.u = ahead.u + mach * c * (1 - ahead.rho / s.behind.rho);
  return s;
}

ReflectedShock reflected_shock(GasState1D behind, double gamma) {
  const GasState1D mirror{behind.rho, -behind.u, behind.p};
  const ExactRiemann r(behind, mirror, gamma);
  ReflectedShock out;
  out.at_wall = r.sample(0.0);
  out.shock_speed = -r.left_wave_speed();
  return out;
}

}  // namespace mpsolid
