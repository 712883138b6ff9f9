#pragma once
// The corrected-gradient models (MODEL.md sections 5 and 7) in any dimension
// (Dim 2 or 3), written for few bytes per particle-step: no per-bond array.
// Each pass is a gather over a particle's bond row that recomputes the bond's
// terms from the two ends' particle data (r0 from the reference positions,
// the weight from |r0|, the hourglass stiffness from the two Young's moduli),
// which the neighbouring rows have just brought into cache. With about 16
// bonds per particle in space, per-bond arrays written and read again each
// step would make the step bandwidth-bound.
//
//   set-up:  A_i = sum_j wl_ij r0_ij (x) r0_ij,   wl_ij = w0_ij / |r0_ij|^2
//   pass 1:  F_i = (sum_j wl_ij r_ij (x) r0_ij) A_i^-1,  J_i = det F_i,  S_i = V P(F_i)
//   pass 1b: (S_i + Q_i) A_i^-1,  Q_i = -1/2 sum_j h_ij g_ij (x) r0_ij (consistent form)
//   pass 2:  f_i = sum_j [ wl_ij ((S + Q)_i A_i^-1 + (S + Q)_j A_j^-1) r0_ij + h_ij g_ij ]
//   g_ij = r_ij - (F_i + F_j) r0_ij / 2,   h_ij = alpha E_ij V (Dim / n0) wl_ij
//
// Every bond term is computed from both ends with the same operations on
// the pair's data: r, r0 and g change sign bit for bit under i <-> j and the
// sums F_i + F_j, S_i + S_j and E_i + E_j do not, so the two ends' force
// terms are exact negatives (momentum kept to the final sums' round-off),
// and each particle's sums run in its row's order: the same bits at any
// thread and rank count. The force pass reads positions (the gaps are not
// stored), so integration waits for every force.
//
// A Law supplies, besides the plane kernels' forms, piola(F, J, lambda, mu,
// strain, pressure) and energy_density(F, lambda, mu) on Dim x Dim Eigen
// matrices.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_shells.hpp"
#include "kernels/hourglass_options.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

// The first Dim of three coordinate arrays.
template <int Dim>
std::array<const double*, Dim> axes(const std::vector<double>& x, const std::vector<double>& y,
                                    const std::vector<double>& z) {
  if constexpr (Dim == 2)
    return {x.data(), y.data()};
  else
    return {x.data(), y.data(), z.data()};
}
// The store's positions now and at set-up, one array per axis.
template <int Dim>
std::array<const double*, Dim> position_arrays(const ParticleStore& p) {
  return axes<Dim>(p.x, p.y, p.z);
}
template <int Dim>
std::array<const double*, Dim> reference_arrays(const ParticleStore& p) {
  return axes<Dim>(p.x0, p.y0, p.z0);
}

template <int Dim, class Law>
class GradientGatherModel {
 public:
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  using Vec = Eigen::Matrix<double, Dim, 1>;
  static constexpr int dimension = Dim;
  static constexpr const char* name = Law::name;
  static constexpr bool uses_rotation = false;
  static constexpr bool rotation_invariant = Law::rotation_invariant;
  static constexpr bool forces_read_positions = true;
  static constexpr const char* options_section = Law::name;
  static std::vector<OptionSpec> options() { return hourglass_option_table(); }

  // Throws InputError if a particle's neighbourhood cannot define A_i^-1.
  GradientGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options)
      : GradientGatherModel(p, bonds, options, p.all()) {}
  // Only the particles in `whole_rows` have their whole bond rows (a rank's
  // own particles): the others' A^-1 is left zero (their F and stress come
  // from their owners).
  GradientGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options,
                      Range whole_rows)
      : volume_(bonds.geometry.volume),
        re_(bonds.geometry.re),
        shells_(find_bond_shells(p, bonds)) {
    for (const double len : shells_.length) shell_wl_.push_back(weight_over_square(len * len));
    if (p.dimension != Dim)
      throw std::logic_error(
          fmt::format("{}: a {}D kernel for a {}D store", name, Dim, p.dimension));
    const HourglassSettings hourglass = hourglass_settings(options);
    consistent_hourglass_ = hourglass.consistent && hourglass.alpha > 0;
    const std::size_t n = p.size();
    penalty_ = hourglass.alpha * volume_ * (Dim / number_density(bonds));
    a_inv_.assign(n, Mat::Zero());
    def_grad_.assign(n, Mat::Identity());
    stress_a_.assign(n, Mat::Zero());
    jacobian_.assign(n, 1.0);
    young_.resize(n);
    for (std::size_t i = 0; i < n; ++i) young_[i] = youngs_modulus(p.lambda[i], p.mu[i]);
    const auto x0 = reference_arrays<Dim>(p);
    for (std::size_t i = whole_rows.begin; i < whole_rows.end; ++i) {
      Mat a = Mat::Zero();
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const Vec r0 = difference(x0, i, bonds.neighbor[b]);
        a.noalias() += weight_over_square(p, i, b, bonds) * r0 * r0.transpose();
      }
      // An interior particle has A = (n0 / Dim) I; neighbours in one plane
      // (one line in 2D) give det A = 0.
      if (!(std::abs(a.determinant()) > 1e-8 * std::pow(a.trace() / Dim, Dim)))
        throw InputError(fmt::format(
            "{}: particle {} at ({}) m has no neighbours off one {}, so its deformation "
            "gradient is undefined; make every body at least 2 particles thick",
            name, p.id[i], fmt::join(reference_point(x0, i), ", "), Dim == 2 ? "line" : "plane"));
      a_inv_[i] = a.inverse();
    }
  }

  // The strain pass with no halo (the whole state on this process).
  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
    NoHalo none;
    strain_pass(p, bonds, range, none);
  }

  // What the halos carry (src/solver/step.hpp): before pass 1 a partner's
  // position, after it its F (a gap reads both ends'), after pass 1b its
  // (S + Q) A^-1 (left posted for the step to finish before the forces).
  template <class Halo>
  static void share_motion(ParticleStore& p, Halo& halo) {
    if constexpr (Dim == 2)
      halo.post("motion", {field_of(p.x), field_of(p.y)});
    else
      halo.post("motion", {field_of(p.x), field_of(p.y), field_of(p.z)});
  }
  template <class Halo>
  void strain_pass(ParticleStore& p, const BondTable& bonds, Range range, Halo& halo) {
    halo.finish();
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) gather_deformation_gradient(p, bonds, i);
    });
    halo.post("deformation gradient", {matrix_field(def_grad_)});
    halo.finish();
    if (consistent_hourglass_)
      parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
        for (std::size_t i = b; i < e; ++i) gather_hourglass_stress(p, bonds, i);
      });
    halo.post("stress", {matrix_field(stress_a_)});  // the step finishes it
  }

  // Pass 2: the force of each moving particle in `range`; no torque.
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) gather_force(p, bonds, i);
    });
  }

  // V W(F_i) + 1/4 sum_j h_ij |g_ij|^2 (needs a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    const auto x = position_arrays<Dim>(p);
    const auto x0 = reference_arrays<Dim>(p);
    double hourglass = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Vec r0 = difference(x0, i, j);
      const double wl = weight_over_square(p, i, b, bonds);
      hourglass += stiffness(i, j, wl) * gap(x, i, j, r0).squaredNorm();
    }
    // Each bond is seen from both ends: a quarter of h |g|^2 per end.
    return volume_ * Law::energy_density(def_grad_[i], p.lambda[i], p.mu[i]) + 0.25 * hourglass;
  }

  // J_i at or below the minimum among the particles of `range`: a collapsed
  // neighbourhood (needs the strain pass at the current state).
  IntegrityReport check_integrity(const ParticleStore&, const BondTable&,
                                  const IntegrityLimits& limits, Range range) const {
    return jacobian_integrity(jacobian_, limits, range);
  }

  // The last strain pass's F_i.
  const Mat& deformation_gradient(std::size_t i) const { return def_grad_[i]; }

 private:
  using Positions = std::array<const double*, Dim>;

  static Vec difference(const Positions& x, std::size_t i, std::size_t j) {
    Vec d;
    for (int a = 0; a < Dim; ++a) d[a] = x[a][j] - x[a][i];
    return d;
  }
  static std::array<double, Dim> reference_point(const Positions& x0, std::size_t i) {
    std::array<double, Dim> out;
    for (int a = 0; a < Dim; ++a) out[a] = x0[a][i];
    return out;
  }
  double weight_over_square(double len2) const {
    return bond_math::weight(std::sqrt(len2), re_) / len2;
  }
  // wl of entry b of row i: its shell's, or computed off the shells.
  double weight_over_square(const ParticleStore& p, std::size_t i, std::uint32_t b,
                            const BondTable& bonds) const {
    const std::uint8_t shell = shells_.of_entry[b];
    if (shell != BondShells::kOff) return shell_wl_[shell];
    return weight_over_square(reference_length2(p, i, bonds.neighbor[b]));
  }
  // h_ij = alpha E_ij V (Dim / n0) wl_ij, E_ij the ends' mean.
  double stiffness(std::size_t i, std::size_t j, double wl) const {
    return penalty_ * (0.5 * (young_[i] + young_[j])) * wl;
  }
  Vec gap(const Positions& x, std::size_t i, std::size_t j, const Vec& r0) const {
    return difference(x, i, j) - 0.5 * ((def_grad_[i] + def_grad_[j]) * r0);
  }
  // Each particle's matrix, its Dim x Dim entries, for a halo.
  static ParticleField matrix_field(std::vector<Mat>& m) {
    return {m.data()->data(), Dim * Dim, Dim * Dim, 1};
  }

  void gather_deformation_gradient(ParticleStore& p, const BondTable& bonds, std::size_t i) {
    const auto x = position_arrays<Dim>(p);
    const auto x0 = reference_arrays<Dim>(p);
    Mat g = Mat::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Vec r0 = difference(x0, i, j);
      g.noalias() += (weight_over_square(p, i, b, bonds) * difference(x, i, j)) * r0.transpose();
    }
    const Mat f = g * a_inv_[i];
    const double jac = f.determinant();
    const Mat stress =
        volume_ * Law::piola(f, jac, p.lambda[i], p.mu[i], p.strain[i], p.pressure[i]);
    def_grad_[i] = f;
    jacobian_[i] = jac;
    stress_a_[i] = stress * a_inv_[i];
  }

  void gather_hourglass_stress(const ParticleStore& p, const BondTable& bonds, std::size_t i) {
    const auto x = position_arrays<Dim>(p);
    const auto x0 = reference_arrays<Dim>(p);
    Mat q = Mat::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Vec r0 = difference(x0, i, j);
      const double h = stiffness(i, j, weight_over_square(p, i, b, bonds));
      q.noalias() += (-0.5 * h * gap(x, i, j, r0)) * r0.transpose();
    }
    stress_a_[i] += q * a_inv_[i];
  }

  void gather_force(ParticleStore& p, const BondTable& bonds, std::size_t i) const {
    const auto x = position_arrays<Dim>(p);
    const auto x0 = reference_arrays<Dim>(p);
    Vec f = Vec::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Vec r0 = difference(x0, i, j);
      const double wl = weight_over_square(p, i, b, bonds);
      f.noalias() += wl * ((stress_a_[i] + stress_a_[j]) * r0);
      f.noalias() += stiffness(i, j, wl) * gap(x, i, j, r0);
    }
    p.fx[i] = f[0];
    p.fy[i] = f[1];
    if constexpr (Dim == 3) p.fz[i] = f[2];
    p.torque[i] = 0.0;
  }

  double volume_, re_;
  BondShells shells_;
  std::vector<double> shell_wl_;  // wl of each shell
  double penalty_ = 0;            // alpha V Dim / n0: h_ij over E_ij wl_ij
  bool consistent_hourglass_ = false;
  std::vector<Mat> a_inv_, def_grad_;  // A_i^-1, F_i
  std::vector<Mat> stress_a_;          // (S_i + Q_i) A_i^-1
  std::vector<double> jacobian_, young_;
};

}  // namespace mpsolid
