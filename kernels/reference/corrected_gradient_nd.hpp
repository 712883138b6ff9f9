#pragma once
// The corrected-gradient models (MODEL.md sections 5 and 7) in any
// dimension, slow and obviously correct: the 2D oracle's pair loop
// (reference_kernels.hpp) with Dim x Dim Eigen matrices, so one text serves
// the plane and space. In 3D the neo-Hookean law is the same formula with
// tr(F^T F) - 3, and the hourglass stiffness h_ij = alpha E V (d / n0) w_ij
// keeps the plane's d / n0 (d = 2 there). A test oracle for 3D kernels;
// in 2D it gives the plane oracle's numbers.
#include <Eigen/Dense>
#include <cmath>
#include <cstddef>
#include <vector>

namespace mpsolid::reference {

template <int Dim>
struct GradientState {
  using Matrix = Eigen::Matrix<double, Dim, Eigen::Dynamic>;
  Matrix x, x0;                                 // positions now and at set-up
  std::vector<double> lambda, mu;               // per particle (Pa)
  std::vector<std::vector<std::size_t>> bonds;  // each particle's neighbours
  double re = 0, n0 = 0, volume = 0;            // m, 1, m^Dim (m^2 times the depth in 2D)
};

template <int Dim>
struct GradientLawNd {
  using M = Eigen::Matrix<double, Dim, Dim>;
  static M neo_hookean_piola(const M& f, double lambda, double mu) {
    const M fit = f.inverse().transpose();
    return mu * (f - fit) + lambda * std::log(f.determinant()) * fit;
  }
  static double neo_hookean_energy(const M& f, double lambda, double mu) {
    const double log_j = std::log(f.determinant());
    return 0.5 * mu * ((f.transpose() * f).trace() - Dim) - mu * log_j +
           0.5 * lambda * log_j * log_j;
  }
};

template <int Dim>
struct GradientResultNd {
  using M = Eigen::Matrix<double, Dim, Dim>;
  std::vector<M> def_grad, piola;
  Eigen::Matrix<double, Dim, Eigen::Dynamic> force;
  double energy = 0;  // sum_i V W(F_i) + sum over bonds of 1/2 h_ij |g_ij|^2
};

// The neo-Hookean finite_strain model; `consistent` adds the hourglass
// energy's dependence on F (the force is then minus the energy's gradient).
template <int Dim>
GradientResultNd<Dim> finite_strain_nd(const GradientState<Dim>& s, double hourglass,
                                       bool consistent) {
  using M = Eigen::Matrix<double, Dim, Dim>;
  using V = Eigen::Matrix<double, Dim, 1>;
  const std::size_t n = s.bonds.size();
  const auto col = [](std::size_t i) { return static_cast<Eigen::Index>(i); };
  const auto r0 = [&](std::size_t i, std::size_t j) {
    return V(s.x0.col(col(j)) - s.x0.col(col(i)));
  };
  const auto r = [&](std::size_t i, std::size_t j) { return V(s.x.col(col(j)) - s.x.col(col(i))); };
  const auto wl = [&](std::size_t i, std::size_t j) {
    const double len = r0(i, j).norm();
    return (s.re / len - 1.0) / (len * len);
  };
  const auto young = [&](std::size_t i) {
    return s.mu[i] * (3 * s.lambda[i] + 2 * s.mu[i]) / (s.lambda[i] + s.mu[i]);
  };
  GradientResultNd<Dim> out;
  std::vector<M> a_inv(n), stress(n);
  out.def_grad.resize(n);
  out.piola.resize(n);
  out.force = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Zero(Dim, col(n));
  for (std::size_t i = 0; i < n; ++i) {
    M a = M::Zero(), g = M::Zero();
    for (const std::size_t j : s.bonds[i]) {
      a += wl(i, j) * r0(i, j) * r0(i, j).transpose();
      g += wl(i, j) * r(i, j) * r0(i, j).transpose();
    }
    a_inv[i] = a.inverse();
    out.def_grad[i] = g * a_inv[i];
    out.piola[i] = GradientLawNd<Dim>::neo_hookean_piola(out.def_grad[i], s.lambda[i], s.mu[i]);
    stress[i] = s.volume * out.piola[i];
    out.energy +=
        s.volume * GradientLawNd<Dim>::neo_hookean_energy(out.def_grad[i], s.lambda[i], s.mu[i]);
  }
  const auto h = [&](std::size_t i, std::size_t j) {
    return hourglass * 0.5 * (young(i) + young(j)) * s.volume * (Dim / s.n0) * wl(i, j);
  };
  const auto gap = [&](std::size_t i, std::size_t j) {
    return V(r(i, j) - 0.5 * (out.def_grad[i] + out.def_grad[j]) * r0(i, j));
  };
  if (consistent)
    for (std::size_t i = 0; i < n; ++i)
      for (const std::size_t j : s.bonds[i])
        stress[i] += -0.5 * h(i, j) * gap(i, j) * r0(i, j).transpose();
  for (std::size_t i = 0; i < n; ++i)
    for (const std::size_t j : s.bonds[i]) {
      if (j < i) continue;
      const V f =
          wl(i, j) * (stress[i] * a_inv[i] + stress[j] * a_inv[j]) * r0(i, j) + h(i, j) * gap(i, j);
      out.force.col(col(i)) += f;
      out.force.col(col(j)) -= f;
      out.energy += 0.5 * h(i, j) * gap(i, j).squaredNorm();
    }
  return out;
}

}  // namespace mpsolid::reference
