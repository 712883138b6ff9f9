#pragma once
// An ideal gas's states in Dim dimensions: primitive (density, velocity,
// pressure) and conserved (density, momentum, total energy per volume), the
// conversions between them and the Euler flux through a face normal to an
// axis. Every function is written for any Dim, so the 3D solver is the 2D
// one instantiated again.
#include <array>
#include <cmath>

namespace mpsolid {

template <int Dim>
struct GasPrimitive {
  double rho = 0;               // kg/m^3
  std::array<double, Dim> u{};  // m/s
  double p = 0;                 // Pa
};

template <int Dim>
struct GasConserved {
  double rho = 0;               // kg/m^3
  std::array<double, Dim> m{};  // momentum per volume, kg/(m^2 s)
  double E = 0;                 // total energy per volume, J/m^3
};

template <int Dim>
double kinetic_energy_density(const GasPrimitive<Dim>& w) {
  double u2 = 0;
  for (int d = 0; d < Dim; ++d) u2 += w.u[d] * w.u[d];
  return 0.5 * w.rho * u2;
}

template <int Dim>
GasConserved<Dim> to_conserved(const GasPrimitive<Dim>& w, double gamma) {
  GasConserved<Dim> q;
  q.rho = w.rho;
  for (int d = 0; d < Dim; ++d) q.m[d] = w.rho * w.u[d];
  q.E = w.p / (gamma - 1) + kinetic_energy_density(w);
  return q;
}

template <int Dim>
GasPrimitive<Dim> to_primitive(const GasConserved<Dim>& q, double gamma) {
  GasPrimitive<Dim> w;
  w.rho = q.rho;
  double m2 = 0;
  for (int d = 0; d < Dim; ++d) {
    w.u[d] = q.m[d] / q.rho;
    m2 += q.m[d] * q.m[d];
  }
  w.p = (gamma - 1) * (q.E - 0.5 * m2 / q.rho);
  return w;
}

inline double sound_speed(double rho, double p, double gamma) {
  return std::sqrt(gamma * p / rho);
}

// The Euler flux through a face whose normal is +axis of state w, whose
// conserved form is q (to_conserved(w)).
template <int Dim>
GasConserved<Dim> euler_flux(const GasPrimitive<Dim>& w, const GasConserved<Dim>& q, int axis) {
  const double un = w.u[axis];
  GasConserved<Dim> f;
  f.rho = q.rho * un;
  for (int d = 0; d < Dim; ++d) f.m[d] = q.m[d] * un;
  f.m[axis] += w.p;
  f.E = (q.E + w.p) * un;
  return f;
}

template <int Dim>
GasConserved<Dim> euler_flux(const GasPrimitive<Dim>& w, double gamma, int axis) {
  return euler_flux(w, to_conserved(w, gamma), axis);
}

}  // namespace mpsolid
