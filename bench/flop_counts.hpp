#pragma once
// Floating-point operations per call of each kernel, counted by hand from the
// code (kernels/*.hpp, src/integrator.cpp, src/rigid_body.cpp): every +, -,
// *, / and sqrt is one flop, a sin, cos or log one flop (so the counts are a
// lower bound), a sign change none. Per bond entry (each bond is seen from
// both ends) and per particle:
//
// paper, paper_conservative
//   half angles   per particle 3     0.5 theta, cos, sin
//   strain pass   per entry 27       bond rotation 6, r_ij and u_ij 10, 1/|r_ij| 5
//                                    (2 mul, add, sqrt, div), u.e 4, eps += 2
//                 per particle 1     p = -lambda eps
//   force pass    per entry 38       rotation, u, 1/|r| 21, C_ij 4, f += k u - C r 8,
//                                    torque k (r x u) 4, sum 1
//                 (conservative +18: u.e / |r| 5, f -= C u^s 8, torque C (u x r) 5)
//                 per particle 1     0.5 torque
//   integration   per particle 18    kick 6, drift 4, spin kick 3, theta 2, half angles 3
// finite_strain
//   strain pass   per entry 14 + 29  pass 1: r_ij 2, G += wl r (x) r0 12;
//                                    pass 1b (consistent hourglass): g_ij 16, h 1, Q += 12
//                 per particle 78    F = G A^-1 12, det 3, log 1, F^-T 4, P 24, S = V P 4,
//                                    S A^-1 12, p 2; pass 1b: Q A^-1 12, S += 4
//   force pass    per entry 34       (S_i + S_j) A^-1 r0 14, g_ij 16, f += h g 4
//   integration   per particle 10    kick 6, drift 4
// linear_elastic: as finite_strain but Hooke's law for the stress
//                 per particle 59    F = G A^-1 12, det 3, eps 3, sigma 7, S = V sigma 4,
//                                    S A^-1 12, strain and p 2; pass 1b: Q A^-1 12, S += 4
// rigid bodies (any model) per particle of a body 26: momentum sums 14, placement 12
#include <string>

namespace mpsolid::bench {

struct FlopCounts {
  double half_angles_particle;
  double strain_entry, strain_particle;
  double force_entry, force_particle;
  double integrate_particle;
};

inline FlopCounts flop_counts(const std::string& model) {
  if (model == "finite_strain") return {0, 14 + 29, 78, 34, 0, 10};
  if (model == "linear_elastic") return {0, 14 + 29, 59, 34, 0, 10};
  if (model == "paper_conservative") return {3, 27, 1, 38 + 18, 1, 18};
  return {3, 27, 1, 38, 1, 18};
}

inline constexpr double kRigidFlopsPerParticle = 26;

}  // namespace mpsolid::bench
