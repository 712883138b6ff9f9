#include "src/gas/exact_riemann.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mpsolid {

namespace {
// Toro's f_K(p) and its derivative: the velocity change across the wave
// that joins the side state (rho, p, c) to pressure p.
struct PressureFunction {
  double f, df;
};
PressureFunction pressure_function(double p, const GasState1D& k, double c, double gamma) {
  if (p > k.p) {  // shock
    const double a = 2 / ((gamma + 1) * k.rho), b = (gamma - 1) / (gamma + 1) * k.p;
    const double root = std::sqrt(a / (p + b));
    return {(p - k.p) * root, root * (1 - 0.5 * (p - k.p) / (b + p))};
  }
  const double ratio = p / k.p, e = (gamma - 1) / (2 * gamma);  // rarefaction
  return {2 * c / (gamma - 1) * (std::pow(ratio, e) - 1),
          1 / (k.rho * c) * std::pow(ratio, -(gamma + 1) / (2 * gamma))};
}
}  // namespace

ExactRiemann::ExactRiemann(GasState1D left, GasState1D right, double gamma)
    : l_(left), r_(right), gamma_(gamma) {
  cl_ = std::sqrt(gamma * l_.p / l_.rho);
  cr_ = std::sqrt(gamma * r_.p / r_.rho);
  const double du = r_.u - l_.u;
  if (2 * (cl_ + cr_) / (gamma - 1) <= du)
    throw std::invalid_argument("the Riemann problem's states create a vacuum");
  // Start from the two-rarefaction guess (positive, close for most states).
  const double e = (gamma - 1) / (2 * gamma);
  double p = std::pow(
      (cl_ + cr_ - 0.5 * (gamma - 1) * du) / (cl_ / std::pow(l_.p, e) + cr_ / std::pow(r_.p, e)),
      1 / e);
  p = std::max(p, 1e-12 * std::min(l_.p, r_.p));
  for (int k = 0; k < 100; ++k) {
    const PressureFunction fl = pressure_function(p, l_, cl_, gamma);
    const PressureFunction fr = pressure_function(p, r_, cr_, gamma);
    double next = p - (fl.f + fr.f + du) / (fl.df + fr.df);
    if (next <= 0) next = 0.1 * p;
    const double change = std::abs(next - p) / (0.5 * (next + p));
    p = next;
    if (change < 1e-15) break;
  }
  p_star_ = p;
  u_star_ = 0.5 * (l_.u + r_.u) +
            0.5 * (pressure_function(p, r_, cr_, gamma).f - pressure_function(p, l_, cl_, gamma).f);
}

double ExactRiemann::left_wave_speed() const {
  if (p_star_ > l_.p)
    return l_.u - cl_ * std::sqrt((gamma_ + 1) / (2 * gamma_) * p_star_ / l_.p +
                                  (gamma_ - 1) / (2 * gamma_));
  return l_.u - cl_;
}

double ExactRiemann::right_wave_speed() const {
  if (p_star_ > r_.p)
    return r_.u + cr_ * std::sqrt((gamma_ + 1) / (2 * gamma_) * p_star_ / r_.p +
                                  (gamma_ - 1) / (2 * gamma_));
  return r_.u + cr_;
}

GasState1D ExactRiemann::sample(double s) const {
  const double g = gamma_, gm = (g - 1) / (g + 1);
  if (s <= u_star_) {  // left of the contact
    const GasState1D& k = l_;
    if (p_star_ > k.p) {
      if (s <= left_wave_speed()) return k;
      const double ratio = p_star_ / k.p;
      return {k.rho * (ratio + gm) / (gm * ratio + 1), u_star_, p_star_};
    }
    const double c_star = cl_ * std::pow(p_star_ / k.p, (g - 1) / (2 * g));
    if (s <= k.u - cl_) return k;
    if (s >= u_star_ - c_star) return {k.rho * std::pow(p_star_ / k.p, 1 / g), u_star_, p_star_};
    const double c = 2 / (g + 1) * (cl_ + 0.5 * (g - 1) * (k.u - s));
    const double u = 2 / (g + 1) * (cl_ + 0.5 * (g - 1) * k.u + s);
    const double rho = k.rho * std::pow(c / cl_, 2 / (g - 1));
    return {rho, u, k.p * std::pow(c / cl_, 2 * g / (g - 1))};
  }
  const GasState1D& k = r_;
  if (p_star_ > k.p) {
    if (s >= right_wave_speed()) return k;
    const double ratio = p_star_ / k.p;
    return {k.rho * (ratio + gm) / (gm * ratio + 1), u_star_, p_star_};
  }
  const double c_star = cr_ * std::pow(p_star_ / k.p, (g - 1) / (2 * g));
  if (s >= k.u + cr_) return k;
  if (s <= u_star_ + c_star) return {k.rho * std::pow(p_star_ / k.p, 1 / g), u_star_, p_star_};
  const double c = 2 / (g + 1) * (cr_ - 0.5 * (g - 1) * (k.u - s));
  const double u = 2 / (g + 1) * (-cr_ + 0.5 * (g - 1) * k.u + s);
  const double rho = k.rho * std::pow(c / cr_, 2 / (g - 1));
  return {rho, u, k.p * std::pow(c / cr_, 2 * g / (g - 1))};
}

}  // namespace mpsolid
