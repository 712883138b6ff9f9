#pragma once
// The HLLC approximate Riemann solver (Toro, Spruce and Speares 1994) for
// the flux through a face normal to `axis`, with Einfeldt's wave-speed
// bounds from Roe averages (Batten et al. 1997): exact for an isolated
// contact or shock, positive for any positive left and right states.
#include <algorithm>
#include <cmath>

#include "src/gas/ideal_gas.hpp"

namespace mpsolid {

template <int Dim>
GasConserved<Dim> hllc_flux(const GasPrimitive<Dim>& l, const GasPrimitive<Dim>& r, double gamma,
                            int axis) {
  // Each side's conserved state, computed once.
  const GasConserved<Dim> ql = to_conserved(l, gamma), qr = to_conserved(r, gamma);
  const double cl = sound_speed(l.rho, l.p, gamma), cr = sound_speed(r.rho, r.p, gamma);
  const double ul = l.u[axis], ur = r.u[axis];
  // Roe averages of the normal velocity and the sound speed.
  const double sl_rho = std::sqrt(l.rho), sr_rho = std::sqrt(r.rho);
  const double hl = (ql.E + l.p) / l.rho;
  const double hr = (qr.E + r.p) / r.rho;
  const double u_roe = (sl_rho * ul + sr_rho * ur) / (sl_rho + sr_rho);
  double q2_roe = 0;
  for (int d = 0; d < Dim; ++d) {
    const double v = (sl_rho * l.u[d] + sr_rho * r.u[d]) / (sl_rho + sr_rho);
    q2_roe += v * v;
  }
  const double h_roe = (sl_rho * hl + sr_rho * hr) / (sl_rho + sr_rho);
  const double c_roe = std::sqrt(std::max((gamma - 1) * (h_roe - 0.5 * q2_roe), 0.0));
  const double s_l = std::min(ul - cl, u_roe - c_roe);
  const double s_r = std::max(ur + cr, u_roe + c_roe);
  if (s_l >= 0) return euler_flux(l, ql, axis);
  if (s_r <= 0) return euler_flux(r, qr, axis);
  const double ml = l.rho * (s_l - ul), mr = r.rho * (s_r - ur);
  const double s_star = (r.p - l.p + ml * ul - mr * ur) / (ml - mr);
  // The star state on the side K and its flux F_K + S_K (U*_K - U_K).
  const auto star_flux = [&](const GasPrimitive<Dim>& w, const GasConserved<Dim>& q, double s,
                             double mass) {
    GasConserved<Dim> f = euler_flux(w, q, axis);
    const double factor = mass / (s - s_star);  // rho_K (S_K - u_K) / (S_K - S*)
    const double un = w.u[axis];
    GasConserved<Dim> star;
    star.rho = factor;
    for (int d = 0; d < Dim; ++d) star.m[d] = factor * w.u[d];
    star.m[axis] = factor * s_star;
    star.E = factor * (q.E / w.rho + (s_star - un) * (s_star + w.p / mass));
    f.rho += s * (star.rho - q.rho);
    for (int d = 0; d < Dim; ++d) f.m[d] += s * (star.m[d] - q.m[d]);
    f.E += s * (star.E - q.E);
    return f;
  };
  return s_star >= 0 ? star_flux(l, ql, s_l, ml) : star_flux(r, qr, s_r, mr);
}

}  // namespace mpsolid
