#pragma once
// The corrected-gradient models (MODEL.md sections 5 and 7) in any dimension
// (Dim 2 or 3), written for few bytes per particle-step: no per-bond array.
// Each pass is a gather over a particle's bond row that recomputes the bond's
// terms from the two ends' particle data (r0 from the reference positions,
// the weight from the bond's lattice shell, the hourglass stiffness from the
// two Young's moduli), which the neighbouring rows have just brought into
// cache. With about 16 bonds per particle in space, per-bond arrays written
// and read again each step would make the step bandwidth-bound.
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
// thread and rank count. Along the row patterns (kernels/row_patterns.hpp)
// the passes take kLanes particles at a time with the same operations lane
// by lane, so every path gives the row by row bits. The per-particle
// matrices are kept component by component (Dim x Dim arrays of n values),
// so that kLanes consecutive particles' entries are one load. The force
// pass reads positions (the gaps are not stored), so integration waits for
// every force.
//
// A Law supplies piola<Dim>(F, J, lambda, mu, out, strain, pressure) on
// row-major Dim x Dim arrays of double or Lanes, and
// energy_density(F, lambda, mu) on a Dim x Dim Eigen matrix.
#include <fmt/format.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_shells.hpp"
#include "kernels/hourglass_options.hpp"
#include "kernels/lanes.hpp"
#include "kernels/model_common.hpp"
#include "kernels/row_patterns.hpp"
#include "kernels/small_matrix.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

template <int Dim, class Law>
class GradientGatherModel {
 public:
  static constexpr int dimension = Dim;
  static constexpr const char* name = Law::name;
  static constexpr bool uses_rotation = false;
  static constexpr bool rotation_invariant = Law::rotation_invariant;
  static constexpr bool forces_read_positions = true;
  static constexpr const char* options_section = Law::name;
  static std::vector<OptionSpec> options() { return hourglass_option_table(); }
  using Mat = Eigen::Matrix<double, Dim, Dim>;

  // Throws InputError if a particle's neighbourhood cannot define A_i^-1.
  GradientGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options)
      : GradientGatherModel(p, bonds, options, p.all()) {}
  // Only the particles in `whole_rows` have their whole bond rows (a rank's
  // own particles): the others' A^-1 is left zero (their F and stress come
  // from their owners).
  GradientGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options,
                      Range whole_rows)
      : n_(p.size()),
        volume_(bonds.geometry.volume),
        re_(bonds.geometry.re),
        shells_(find_bond_shells(p, bonds)),
        rows_(find_row_patterns(bonds, shells_.of_entry, BondShells::kOff)) {
    for (const double len : shells_.length) shell_wl_.push_back(weight_over_square(len * len));
    if (p.dimension != Dim)
      throw std::logic_error(
          fmt::format("{}: a {}D kernel for a {}D store", name, Dim, p.dimension));
    const HourglassSettings hourglass = hourglass_settings(options);
    consistent_hourglass_ = hourglass.consistent && hourglass.alpha > 0;
    penalty_ = hourglass.alpha * volume_ * (Dim / number_density(bonds));
    a_inv_.assign(kEntries * n_, 0.0);
    def_grad_.assign(kEntries * n_, 0.0);
    for (int a = 0; a < Dim; ++a)
      std::fill_n(def_grad_.begin() + static_cast<std::ptrdiff_t>((a * Dim + a) * n_), n_, 1.0);
    stress_a_.assign(kEntries * n_, 0.0);
    jacobian_.assign(n_, 1.0);
    young_.resize(n_);
    for (std::size_t i = 0; i < n_; ++i) young_[i] = youngs_modulus(p.lambda[i], p.mu[i]);
    for (std::size_t i = whole_rows.begin; i < whole_rows.end; ++i) {
      Mat a = Mat::Zero();
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const Eigen::Matrix<double, Dim, 1> r0 = reference_bond(p, i, j);
        a.noalias() += wl_of(p, i, {j, shells_.of_entry[b]}) * r0 * r0.transpose();
      }
      // An interior particle has A = (n0 / Dim) I; neighbours in one plane
      // (one line in 2D) give det A = 0.
      if (!(std::abs(a.determinant()) > 1e-8 * std::pow(a.trace() / Dim, Dim)))
        throw InputError(fmt::format(
            "{}: particle {} at ({}) m has no neighbours off one {}, so its deformation "
            "gradient is undefined; make every body at least 2 particles thick",
            name, p.id[i], fmt::join(reference_point(p, i), ", "), Dim == 2 ? "line" : "plane"));
      const Mat inverse = a.inverse();
      for (int r = 0; r < Dim; ++r)
        for (int c = 0; c < Dim; ++c) a_inv_[(r * Dim + c) * n_ + i] = inverse(r, c);
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
    gather_range(
        rows_, bonds, shells_.of_entry, range,
        [&](auto tag, std::size_t i, std::size_t count, auto&& entry, auto&& keep, FreshLanes) {
          gather_deformation_gradient<decltype(tag)>(p, i, count, entry, keep);
        });
    halo.post("deformation gradient", {matrix_field(def_grad_)});
    halo.finish();
    if (consistent_hourglass_)
      gather_range(rows_, bonds, shells_.of_entry, range,
                   [&](auto tag, std::size_t i, std::size_t count, auto&& entry, auto&& keep,
                       FreshLanes fresh) {
                     gather_hourglass_stress<decltype(tag)>(p, i, count, entry, keep, fresh);
                   });
    halo.post("stress", {matrix_field(stress_a_)});  // the step finishes it
  }

  // Pass 2: the force of each moving particle in `range`; no torque.
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    gather_range(rows_, bonds, shells_.of_entry, range,
                 [&](auto tag, std::size_t i, std::size_t count, auto&& entry, auto&& keep,
                     FreshLanes) { gather_force<decltype(tag)>(p, i, count, entry, keep); });
  }

  // Each particle row by row, as where no pattern fits (the tests' check
  // that every path gives the same bits).
  void take_rows_one_by_one() { rows_ = row_by_row(n_); }

  // V W(F_i) + 1/4 sum_j h_ij |g_ij|^2 (needs a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    const End<double> a = end_of<double>(p, i);
    const SmallMatrix<Dim, double> fi = matrix_at<double>(def_grad_, i);
    double hourglass = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const double h =
          stiffness<double>(young_[i], young_[j], wl_of(p, i, {j, shells_.of_entry[b]}));
      const auto g = gap<double>(a, end_of<double>(p, j), fi, matrix_at<double>(def_grad_, j));
      double g2 = 0.0;
      for (int d = 0; d < Dim; ++d) g2 += g[d] * g[d];
      hourglass += h * g2;
    }
    // Each bond is seen from both ends: a quarter of h |g|^2 per end.
    return volume_ * Law::energy_density(deformation_gradient(i), p.lambda[i], p.mu[i]) +
           0.25 * hourglass;
  }

  // J_i at or below the minimum among the particles of `range`: a collapsed
  // neighbourhood (needs the strain pass at the current state).
  IntegrityReport check_integrity(const ParticleStore&, const BondTable&,
                                  const IntegrityLimits& limits, Range range) const {
    return jacobian_integrity(jacobian_, limits, range);
  }

  // The last strain pass's F_i.
  Mat deformation_gradient(std::size_t i) const {
    Mat f;
    for (int r = 0; r < Dim; ++r)
      for (int c = 0; c < Dim; ++c) f(r, c) = def_grad_[(r * Dim + c) * n_ + i];
    return f;
  }

 private:
  static constexpr int kEntries = Dim * Dim;
  template <class T>
  using Matrix = SmallMatrix<Dim, T>;

  // A particle's (or kLanes particles') position and reference position.
  template <class T>
  struct End {
    std::array<T, Dim> x, x0;
  };
  template <class T, class J>
  static End<T> end_of(const ParticleStore& p, J i) {
    const std::array<const std::vector<double>*, 3> now{&p.x, &p.y, &p.z}, ref{&p.x0, &p.y0, &p.z0};
    End<T> e;
    for (int a = 0; a < Dim; ++a) {
      e.x[a] = load_at<T>(now[a]->data(), i);
      e.x0[a] = load_at<T>(ref[a]->data(), i);
    }
    return e;
  }
  template <class T, class J>
  Matrix<T> matrix_at(const std::vector<double>& m, J i) const {
    Matrix<T> out;
    for (int c = 0; c < kEntries; ++c) out[c] = load_at<T>(m.data() + c * n_, i);
    return out;
  }
  template <class T>
  void store_matrix(std::vector<double>& m, std::size_t i, const Matrix<T>& v) {
    for (int c = 0; c < kEntries; ++c) store_to(m.data() + c * n_ + i, v[c]);
  }
  // Each particle's matrix (Dim x Dim arrays of n values) for a halo.
  ParticleField matrix_field(std::vector<double>& m) const { return {m.data(), kEntries, 1, n_}; }

  static Eigen::Matrix<double, Dim, 1> reference_bond(const ParticleStore& p, std::size_t i,
                                                      std::size_t j) {
    const End<double> a = end_of<double>(p, i), b = end_of<double>(p, j);
    Eigen::Matrix<double, Dim, 1> r0;
    for (int d = 0; d < Dim; ++d) r0[d] = b.x0[d] - a.x0[d];
    return r0;
  }
  static std::array<double, Dim> reference_point(const ParticleStore& p, std::size_t i) {
    return end_of<double>(p, i).x0;
  }
  double weight_over_square(double len2) const {
    return bond_math::weight(std::sqrt(len2), re_) / len2;
  }
  // wl of an entry of particle i's row: its shell's, or computed off the
  // shells.
  double wl_of(const ParticleStore& p, std::size_t i, RowEntry e) const {
    if (e.shell < shell_wl_.size()) return shell_wl_[e.shell];
    return weight_over_square(reference_length2(p, i, e.partner));
  }
  // The entries of kLanes particles' own rows: each lane's wl.
  Lanes wl_of(const ParticleStore& p, std::size_t i, const LaneEntry& e) const {
    Lanes wl;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const auto shell = static_cast<std::size_t>(e.shell[l]);
      wl[l] = shell < shell_wl_.size() ? shell_wl_[shell]
                                       : weight_over_square(reference_length2(
                                             p, i + l, static_cast<std::size_t>(e.partner[l])));
    }
    return wl;
  }
  // h_ij = alpha E_ij V (Dim / n0) wl_ij, E_ij the ends' mean.
  template <class T, class W>
  T stiffness(T young_i, T young_j, W wl) const {
    return penalty_ * (0.5 * (young_i + young_j)) * wl;
  }
  // r_ij - (F_i + F_j) r0_ij / 2.
  template <class T>
  static std::array<T, Dim> gap(const End<T>& a, const End<T>& b, const Matrix<T>& fi,
                                const Matrix<T>& fj) {
    std::array<T, Dim> r0, g;
    for (int d = 0; d < Dim; ++d) r0[d] = b.x0[d] - a.x0[d];
    for (int r = 0; r < Dim; ++r) {
      T turned = (fi[r * Dim] + fj[r * Dim]) * r0[0];
      for (int c = 1; c < Dim; ++c) turned += (fi[r * Dim + c] + fj[r * Dim + c]) * r0[c];
      g[r] = (b.x[r] - a.x[r]) - 0.5 * turned;
    }
    return g;
  }

  // Pass 1 for particle i or kLanes from i. A masked entry's terms are
  // selected away (kernels/row_patterns.hpp), whatever its partner holds.
  template <class T, class Entries, class Keep>
  void gather_deformation_gradient(ParticleStore& p, std::size_t i, std::size_t count,
                                   Entries&& entries, Keep&& keep) {
    const End<T> a = end_of<T>(p, i);
    Matrix<T> g{};
    for (std::size_t n = 0; n < count; ++n) {
      const auto e = entries(n);
      const End<T> b = end_of<T>(p, e.partner);
      const T wl = broadcast<T>(wl_of(p, i, e));
      for (int r = 0; r < Dim; ++r) {
        const T scaled = keep(n, wl * (b.x[r] - a.x[r]));
        for (int c = 0; c < Dim; ++c) g[r * Dim + c] += scaled * (b.x0[c] - a.x0[c]);
      }
    }
    const Matrix<T> a_inv = matrix_at<T>(a_inv_, i);
    const Matrix<T> f = matrix_product<Dim>(g, a_inv);
    const T jac = determinant<Dim>(f);
    Matrix<T> stress;
    T strain, pressure;
    Law::template piola<Dim>(f.data(), jac, load_as<T>(&p.lambda[i]), load_as<T>(&p.mu[i]),
                             stress.data(), strain, pressure);
    for (T& s : stress) s = volume_ * s;
    store_matrix(def_grad_, i, f);
    store_to(&jacobian_[i], jac);
    store_matrix(stress_a_, i, matrix_product<Dim>(stress, a_inv));
    store_to(&p.strain[i], strain);
    store_to(&p.pressure[i], pressure);
  }

  // Pass 1b: (S_i + Q_i) A_i^-1.
  // It adds to (S_i) A_i^-1: only its fresh lanes are written.
  template <class T, class Entries, class Keep>
  void gather_hourglass_stress(const ParticleStore& p, std::size_t i, std::size_t count,
                               Entries&& entries, Keep&& keep, FreshLanes fresh) {
    const End<T> a = end_of<T>(p, i);
    const Matrix<T> fi = matrix_at<T>(def_grad_, i);
    const T young_i = load_as<T>(&young_[i]);
    Matrix<T> q{};
    for (std::size_t n = 0; n < count; ++n) {
      const auto e = entries(n);
      const End<T> b = end_of<T>(p, e.partner);
      const T h =
          stiffness<T>(young_i, load_at<T>(young_.data(), e.partner), broadcast<T>(wl_of(p, i, e)));
      const std::array<T, Dim> g = gap<T>(a, b, fi, matrix_at<T>(def_grad_, e.partner));
      for (int r = 0; r < Dim; ++r) {
        const T scaled = keep(n, (-0.5 * h) * g[r]);
        for (int c = 0; c < Dim; ++c) q[r * Dim + c] += scaled * (b.x0[c] - a.x0[c]);
      }
    }
    const Matrix<T> qa = matrix_product<Dim>(q, matrix_at<T>(a_inv_, i));
    const Matrix<T> sa = matrix_at<T>(stress_a_, i);
    for (int c = 0; c < kEntries; ++c) store_fresh(&stress_a_[c * n_ + i], sa[c] + qa[c], fresh);
  }

  // Pass 2.
  template <class T, class Entries, class Keep>
  void gather_force(ParticleStore& p, std::size_t i, std::size_t count, Entries&& entries,
                    Keep&& keep) const {
    const End<T> a = end_of<T>(p, i);
    const Matrix<T> fi = matrix_at<T>(def_grad_, i), sai = matrix_at<T>(stress_a_, i);
    const T young_i = load_as<T>(&young_[i]);
    std::array<T, Dim> f{};
    for (std::size_t n = 0; n < count; ++n) {
      const auto e = entries(n);
      const End<T> b = end_of<T>(p, e.partner);
      const T wl = broadcast<T>(wl_of(p, i, e));
      const T h = stiffness<T>(young_i, load_at<T>(young_.data(), e.partner), wl);
      const Matrix<T> saj = matrix_at<T>(stress_a_, e.partner);
      const std::array<T, Dim> g = gap<T>(a, b, fi, matrix_at<T>(def_grad_, e.partner));
      for (int r = 0; r < Dim; ++r) {
        T traction = (sai[r * Dim] + saj[r * Dim]) * (b.x0[0] - a.x0[0]);
        for (int c = 1; c < Dim; ++c)
          traction += (sai[r * Dim + c] + saj[r * Dim + c]) * (b.x0[c] - a.x0[c]);
        f[r] += keep(n, wl * traction + h * g[r]);
      }
    }
    store_to(&p.fx[i], f[0]);
    store_to(&p.fy[i], f[1]);
    if constexpr (Dim == 3) store_to(&p.fz[i], f[2]);
    store_to(&p.torque[i], T{});
  }

  std::size_t n_;
  double volume_, re_;
  BondShells shells_;
  RowPatterns rows_;
  std::vector<double> shell_wl_;  // wl of each shell
  double penalty_ = 0;            // alpha V Dim / n0: h_ij over E_ij wl_ij
  bool consistent_hourglass_ = false;
  // Dim x Dim arrays of n values: A_i^-1, F_i, (S_i + Q_i) A_i^-1.
  std::vector<double> a_inv_, def_grad_, stress_a_;
  std::vector<double> jacobian_, young_;
};

}  // namespace mpsolid
