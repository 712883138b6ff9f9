#pragma once
// The exact solution of the 1D Riemann problem for an ideal gas (Toro,
// "Riemann Solvers and Numerical Methods for Fluid Dynamics", chapter 4):
// the star region's pressure and velocity by Newton's method on the
// pressure function, and the self-similar solution sampled at x / t. The
// reference for the gas solver's tests and for the shock relations.
namespace mpsolid {

struct GasState1D {
  double rho = 0, u = 0, p = 0;
};

class ExactRiemann {
 public:
  // Throws std::invalid_argument when the states create a vacuum.
  ExactRiemann(GasState1D left, GasState1D right, double gamma);
  double star_pressure() const { return p_star_; }
  double star_velocity() const { return u_star_; }
  // The state at speed s = x / t (the discontinuity's start at x = 0).
  GasState1D sample(double s) const;
  // The speeds of the left and right waves' fronts: a shock's speed, or a
  // rarefaction's head.
  double left_wave_speed() const;
  double right_wave_speed() const;

 private:
  GasState1D l_, r_;
  double gamma_, cl_, cr_, p_star_ = 0, u_star_ = 0;
};

}  // namespace mpsolid
