#pragma once
// The models built on the kernel-corrected deformation gradient (MODEL.md
// sections 5 and 7), written once over a material law: a total-Lagrangian F
// per particle, the law's first Piola-Kirchhoff stress P(F), and the
// hourglass penalty. No rotation degree of freedom: F carries the rotation,
// so the step skips half angles and spins.
//
// Set-up, per particle:  A_i = sum_j wl_ij r0_ij (x) r0_ij,   wl_ij = w0_ij / |r0_ij|^2
// Pass 1 (all particles): F_i = (sum_j wl_ij r_ij (x) r0_ij) A_i^-1,  J_i = det F_i,
//   S_i = V P(F_i)
// Pass 1b (consistent hourglass, the default): S_i += Q_i = -1/2 sum_j h_ij g_ij (x) r0_ij
// Pass 2 (moving particles):
//   f_i = sum_j [ wl_ij (S_i A_i^-1 + S_j A_j^-1) r0_ij + h_ij g_ij ],
//   g_ij = r_ij - (F_i + F_j) r0_ij / 2,   h_ij = alpha E_ij V (2 / n0) wl_ij.
// S_i = V dW/dF_i makes the first term exactly -d/dr_i of sum_i V W(F_i); the
// hourglass energy E_hg = sum over bonds of 1/2 h_ij |g_ij|^2 depends on the
// positions through F too, and Q_i = dE_hg/dF_i is that part of its
// gradient (pass 1b needs F_j, so it follows pass 1 for every particle). The
// force is then the exact gradient of the total energy: energy is conserved
// to O(dt). MODEL.md's literal form (F held fixed) is hourglass_form =
// "frozen"; it loses about 0.5 % of the external work on the 11.2 kN rod.
//
// Each bond once (kernels/bond_slots.hpp): after pass 1, the bond's owner
// computes its hourglass gap g_ij into its slot. Under i <-> j, r, g and r0
// change sign bit for bit, so the terms of G and Q (products of two of them)
// are the same from both ends and the force terms (linear in r0 and g, with
// S_i + S_j the same sum from either end) are negated: every gather computes
// its terms from the owner's r0 and g, each particle in CSR order, and gets
// the bits it computed for itself before. The force pass reads no position:
// a block's forces and its integration run with no barrier between.
//
// A Law (kernels/finite_strain_model.hpp, kernels/linear_elastic_model.hpp)
// supplies: name (also its case section), rotation_invariant, and
//   piola(f, J, lambda, mu, P, strain, pressure): P(F) and the outputs;
//   energy_density(f, J, lambda, mu): W(F).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_slots.hpp"
#include "kernels/hourglass_options.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

namespace tensor2 {
// Row-major 2x2: m[0] m[1] / m[2] m[3].
// T: double, or Lanes (eight tensors, component by component).
template <class T>
inline T det(const T* m) {
  return m[0] * m[3] - m[1] * m[2];
}

// out = m A^-1 (row-major 2x2).
template <class T>
inline void times_a_inv(const T* m, const T* a_inv, T* out) {
  out[0] = m[0] * a_inv[0] + m[1] * a_inv[2];
  out[1] = m[0] * a_inv[1] + m[1] * a_inv[3];
  out[2] = m[2] * a_inv[0] + m[3] * a_inv[2];
  out[3] = m[2] * a_inv[1] + m[3] * a_inv[3];
}
}  // namespace tensor2

template <class Law>
class CorrectedGradientModel {
 public:
  static constexpr const char* name = Law::name;
  static constexpr bool uses_rotation = false;
  static constexpr bool rotation_invariant = Law::rotation_invariant;
  // The force pass reads only the slots (the strain pass computed the
  // hourglass gaps from the positions): forces and integration share a loop.
  static constexpr bool forces_read_positions = false;
  static constexpr const char* options_section = Law::name;
  static std::vector<OptionSpec> options() { return hourglass_option_table(); }

  // Throws InputError if a particle's neighbourhood cannot define A_i^-1.
  CorrectedGradientModel(const ParticleStore& p, const BondTable& bonds,
                         const OptionValues& options)
      : CorrectedGradientModel(p, bonds, options, p.all()) {}
  // Only the particles in `whole_rows` have their whole bond rows (a rank's
  // own particles, docs/mpi.md): the others' A^-1 is left zero (their F
  // and stress come from their owners).
  CorrectedGradientModel(const ParticleStore& p, const BondTable& bonds,
                         const OptionValues& options, Range whole_rows)
      : volume_(bonds.geometry.volume), slots_(make_bond_slots(bonds)) {
    const HourglassSettings hourglass = hourglass_settings(options);
    consistent_hourglass_ = hourglass.consistent && hourglass.alpha > 0;
    const std::size_t n = p.size();
    const double n0 = number_density(bonds);
    a_inv_.assign(4 * n, 0.0);
    def_grad_.assign(4 * n, 0.0);
    stress_a_.assign(4 * n, 0.0);
    jacobian_.assign(n, 1.0);
    std::vector<double> wl_of(bonds.entry_count());
    std::vector<double> penalty(bonds.entry_count());
    for (std::size_t i = 0; i < n; ++i) {
      double a[4] = {0, 0, 0, 0};
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
        const double len2 = r0x * r0x + r0y * r0y;
        const double wl = bond_math::weight(std::sqrt(len2), bonds.geometry.re) / len2;
        a[0] += wl * r0x * r0x;
        a[1] += wl * r0x * r0y;
        a[2] += wl * r0y * r0x;
        a[3] += wl * r0y * r0y;
        const double e_ij =
            0.5 * (youngs_modulus(p.lambda[i], p.mu[i]) + youngs_modulus(p.lambda[j], p.mu[j]));
        wl_of[b] = wl;
        penalty[b] = hourglass.alpha * e_ij * volume_ * (2.0 / n0) * wl;
      }
      if (i < whole_rows.begin || i >= whole_rows.end) continue;
      const double d = tensor2::det(a);
      // An interior particle has A = (n0 / d) I; neighbours on one line give det A = 0.
      if (!(std::abs(d) > 1e-8 * (a[0] * a[0] + a[3] * a[3])))
        throw InputError(fmt::format(
            "{}: particle {} at ({}, {}) m has no neighbours off one line, so its "
            "deformation gradient is undefined; make every body at least 2 particles thick",
            name, p.id[i], p.x0[i], p.y0[i]));
      double* inv = &a_inv_[4 * i];
      inv[0] = a[3] / d;
      inv[1] = -a[1] / d;
      inv[2] = -a[2] / d;
      inv[3] = a[0] / d;
    }
    // Per slot: the owner's entry's constants (the same from both ends, but
    // r0, which the other end sees negated).
    slot_ = SlotArrays(kFields, slots_.slot_count());
    const auto fill = [&](Field f, const std::vector<double>& per_entry) {
      fill_slot_array(slots_, bonds, per_entry, slot_[f]);
    };
    fill(kR0x, bonds.r0x);
    fill(kR0y, bonds.r0y);
    fill(kWl, wl_of);
    fill(kHourglass, penalty);
  }

  // Pass 1 with no halo (the whole state on this process).
  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
    NoHalo none;
    strain_pass(p, bonds, range, none);
  }

  // What the step's halos carry between ranks or threads (src/solver/step.hpp;
  // on one thread `halo` does nothing): before pass 1, a partner's position
  // (posted by share_motion, received as pass 1 starts); after
  // it, its F (a bond's gap reads both ends'); after pass 1b, its
  // (S + Q) A^-1, which the force pass reads (left posted for the step to
  // finish). A ghost's A^-1 is never read.
  template <class Halo>
  static void share_motion(ParticleStore& p, Halo& halo) {
    halo.post("motion", {field_of(p.x), field_of(p.y)});
  }
  // Pass 1 (F, J, S A^-1) and, with the consistent hourglass, pass 1b (Q).
  template <class Halo>
  void strain_pass(ParticleStore& p, const BondTable& bonds, Range range, Halo& halo) {
    halo.finish();
    compute_deformation_gradient(p, bonds, range);
    // The gaps between two particles of `range` read no ghost's F: on a part
    // they are computed while the F halo travels.
    halo.post("deformation gradient", {deformation_gradient_field()});
    compute_gaps(p, range, range);
    halo.finish();
    compute_gaps_with_ghosts(p, range);
    gather_hourglass(bonds, range);
    halo.post("stress", {stress_field()});  // the step finishes it
  }

  // The strain pass's two parts: pass 1, then (once every particle's F is
  // current) the bonds' gaps and pass 1b.
  void compute_deformation_gradient(ParticleStore& p, const BondTable& bonds, Range range) {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      gather_deformation_gradient(p, bonds, {b, e});
    });
  }
  // The gaps the particles of `range` read (bonds between two of a part's
  // ghosts are never read), then pass 1b.
  void compute_hourglass_stress(const ParticleStore& p, const BondTable& bonds, Range range) {
    compute_gaps(p, range, range);
    compute_gaps_with_ghosts(p, range);
    gather_hourglass(bonds, range);
  }

  // The gaps of the bonds owned in `owners` whose partner is in `partners`.
  void compute_gaps(const ParticleStore& p, Range owners, Range partners) {
    parallel_blocks(owners.begin, owners.end, [&](std::size_t b, std::size_t e) {
      compute_gap_slots(p, {b, e}, partners);
    });
  }
  // The gaps with one end outside `range` that its particles read: owned
  // below it and reaching into it, or owned in it and reaching above.
  void compute_gaps_with_ghosts(const ParticleStore& p, Range range) {
    const std::size_t n = p.size();
    if (range.begin > 0) compute_gaps(p, {0, range.begin}, {range.begin, n});
    if (range.end < n) compute_gaps(p, range, {range.end, n});
  }
  void gather_hourglass(const BondTable& bonds, Range range) {
    if (consistent_hourglass_)
      parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
        gather_hourglass_stress(bonds, {b, e});
      });
  }

  // The per-particle fields the halos carry: F and (S + Q) A^-1.
  ParticleField deformation_gradient_field() { return {def_grad_.data(), 4, 4, 1}; }
  ParticleField stress_field() { return {stress_a_.data(), 4, 1, particle_count()}; }

  // Pass 2: the force; no torque (needs pass 1 at the current state).
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      compute_forces_block(p, bonds, {b, e});
    });
  }

  // Pass 2 on one block, serially (the step fuses it with the integration):
  // per entry, the bond's stress term wl ((S_i + S_j) A^-1) r0 and hourglass
  // force h g as its owner computes them (r0 and g from the slot; S_i + S_j
  // is the same sum from either end), added by the owner and subtracted by
  // the other end, in CSR order.
  void compute_forces_block(ParticleStore& p, const BondTable& bonds, Range block) const {
    const auto stress_a = [&](std::size_t c) { return &stress_a_[c * particle_count()]; };
    gather_lanes(
        slots_, block,
        [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t) {
          Lanes fx{}, fy{}, si[4];
          for (std::size_t c = 0; c < 4; ++c) si[c] = load_lanes(stress_a(c) + m);
          for (std::size_t k = 0; k < pattern.slot_shift.size(); ++k) {
            const std::size_t s = m + pattern.slot_shift[k], j = m + pattern.partner_shift[k];
            const auto at = [&](Field f) { return load_lanes(slot_[f] + s); };
            const auto sum = [&](std::size_t c) { return si[c] + load_lanes(stress_a(c) + j); };
            const auto add = [&](auto owner) {
              add_bond_force<owner()>(fx, fy, sum(0), sum(1), sum(2), sum(3), at(kWl), at(kR0x),
                                      at(kR0y), at(kHourglass), at(kGapX), at(kGapY));
            };
            if (pattern.partner_shift[k] > 0)
              add(std::true_type{});
            else
              add(std::false_type{});
          }
          store_lanes(&p.fx[m], fx);
          store_lanes(&p.fy[m], fy);
          store_lanes(&p.torque[m], Lanes{});
        },
        [&](std::size_t i) {
          double fxi = 0.0, fyi = 0.0;
          for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
            const std::size_t j = bonds.neighbor[b], s = slots_.entry_slot[b];
            const auto at = [&](Field f) { return slot_[f][s]; };
            const auto sum = [&](std::size_t c) { return stress_a(c)[i] + stress_a(c)[j]; };
            const auto add = [&](auto owner) {
              add_bond_force<owner()>(fxi, fyi, sum(0), sum(1), sum(2), sum(3), at(kWl), at(kR0x),
                                      at(kR0y), at(kHourglass), at(kGapX), at(kGapY));
            };
            if (j > i)
              add(std::true_type{});
            else
              add(std::false_type{});
          }
          p.fx[i] = fxi;
          p.fy[i] = fyi;
          p.torque[i] = 0.0;
        });
  }

  // V W(F_i) + 1/4 sum_j h_ij |g_ij|^2 (needs a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    const double density =
        Law::energy_density(&def_grad_[4 * i], jacobian_[i], p.lambda[i], p.mu[i]);
    double hourglass = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t s = slots_.entry_slot[b];  // the other end's g is -g: the same square
      const double gx = slot_[kGapX][s], gy = slot_[kGapY][s];
      hourglass += slot_[kHourglass][s] * (gx * gx + gy * gy);
    }
    // Each bond is seen from both ends: a quarter of h |g|^2 per end.
    return volume_ * density + 0.25 * hourglass;
  }

  // J_i at or below the minimum among the particles of `range`: a collapsed
  // neighbourhood (needs the strain pass at the current state).
  IntegrityReport check_integrity(const ParticleStore&, const BondTable&,
                                  const IntegrityLimits& limits, Range range) const {
    return jacobian_integrity(jacobian_, limits, range);
  }

  // Row-major 2x2 tensors per particle, from the last strain pass.
  const std::vector<double>& deformation_gradient() const { return def_grad_; }
  const std::vector<double>& jacobian() const { return jacobian_; }
  // The law's first Piola-Kirchhoff stress of particle i (row-major).
  std::array<double, 4> stress(const ParticleStore& p, std::size_t i) const {
    std::array<double, 4> piola{};
    double strain = 0, pressure = 0;
    Law::piola(&def_grad_[4 * i], jacobian_[i], p.lambda[i], p.mu[i], piola.data(), strain,
               pressure);
    return piola;
  }

 private:
  std::size_t particle_count() const { return jacobian_.size(); }

  // Pass 1: G_i = sum over its bonds of wl_ij r_ij (x) r0_ij in CSR order;
  // F_i = G_i A_i^-1, J_i, the law's stress and S_i A_i^-1. Each term is
  // computed as the bond's owner (its lower end) sees it, r from the owner
  // to the other end and r0 from its slot: the same bits from both ends (r
  // and r0 both change sign), with no pass that stores them.
  void gather_deformation_gradient(ParticleStore& p, const BondTable& bonds, Range block) {
    const auto finish = [&](std::size_t i, const double* g) {
      const double* ai = &a_inv_[4 * i];
      double* f = &def_grad_[4 * i];
      tensor2::times_a_inv(g, ai, f);
      const double jac = tensor2::det(f);
      double stress[4];
      Law::piola(f, jac, p.lambda[i], p.mu[i], stress, p.strain[i], p.pressure[i]);
      for (double& v : stress) v *= volume_;  // S = V P
      double stress_a[4];
      tensor2::times_a_inv(stress, ai, stress_a);
      for (std::size_t c = 0; c < 4; ++c) stress_a_[c * particle_count() + i] = stress_a[c];
      jacobian_[i] = jac;
    };
    // finish() for particles m .. m + kLanes - 1, lane by lane the same
    // operations (F and A^-1 are rows of 4 per particle).
    const auto finish_lanes = [&](std::size_t m, const Lanes* g) {
      Lanes ai[4], f[4], stress[4], stress_a[4], strain, pressure;
      for (std::size_t c = 0; c < 4; ++c) ai[c] = load_strided(&a_inv_[4 * m], 4, c);
      tensor2::times_a_inv(g, ai, f);
      const Lanes jac = tensor2::det(f);
      Law::piola(f, jac, load_lanes(&p.lambda[m]), load_lanes(&p.mu[m]), stress, strain, pressure);
      for (Lanes& v : stress) v *= volume_;  // S = V P
      tensor2::times_a_inv(stress, ai, stress_a);
      for (std::size_t c = 0; c < 4; ++c) {
        store_strided(&def_grad_[4 * m], 4, c, f[c]);
        store_lanes(&stress_a_[c * particle_count() + m], stress_a[c]);
      }
      store_lanes(&p.strain[m], strain);
      store_lanes(&p.pressure[m], pressure);
      store_lanes(&jacobian_[m], jac);
    };
    gather_lanes(
        slots_, block,
        [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t) {
          const Lanes xi = load_lanes(&p.x[m]), yi = load_lanes(&p.y[m]);
          Lanes g[4] = {};
          for (std::size_t k = 0; k < pattern.slot_shift.size(); ++k) {
            const std::size_t s = m + pattern.slot_shift[k], j = m + pattern.partner_shift[k];
            const Lanes xj = load_lanes(&p.x[j]), yj = load_lanes(&p.y[j]);
            const bool owner = pattern.partner_shift[k] > 0;
            add_gradient_terms(g, owner ? xj - xi : xi - xj, owner ? yj - yi : yi - yj,
                               load_lanes(slot_[kWl] + s), load_lanes(slot_[kR0x] + s),
                               load_lanes(slot_[kR0y] + s));
          }
          finish_lanes(m, g);  // overwrites only: the overlapped lanes get the same bits
        },
        [&](std::size_t i) {
          double g[4] = {0, 0, 0, 0};
          for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
            const std::size_t j = bonds.neighbor[b], s = slots_.entry_slot[b];
            const std::size_t owner = std::min(i, j), other = std::max(i, j);
            add_gradient_terms(g, p.x[other] - p.x[owner], p.y[other] - p.y[owner], slot_[kWl][s],
                               slot_[kR0x][s], slot_[kR0y][s]);
          }
          finish(i, g);
        });
  }

  // G += wl r (x) r0 (T: double or Lanes).
  template <class T>
  static void add_gradient_terms(T* g, T rx, T ry, T wl, T r0x, T r0y) {
    g[0] += wl * rx * r0x;
    g[1] += wl * rx * r0y;
    g[2] += wl * ry * r0x;
    g[3] += wl * ry * r0y;
  }

  // Each owned bond's hourglass gap g_ij = r_ij - (F_i + F_j) r0_ij / 2, as
  // its owner sees it (the other end's is -g bit for bit).
  void compute_gap_slots(const ParticleStore& p, Range owners, Range partners) {
    const auto at = [&](Field f, std::size_t s) { return slot_[f] + s; };
    const auto gaps = [&](std::size_t count, std::size_t s, std::size_t i, std::size_t j) {
      gap_terms(count, &p.x[i], &p.y[i], &p.x[j], &p.y[j], &def_grad_[4 * i], &def_grad_[4 * j],
                at(kR0x, s), at(kR0y, s), at(kGapX, s), at(kGapY, s));
    };
    for_each_owned_slot(
        slots_, owners, 0,
        gaps,  // walls' own bonds too: their Q enters their neighbours' force
        [&](std::size_t s, std::size_t i, std::size_t j) { gaps(1, s, i, j); }, partners);
  }

  // Pass 1b: Q_i = sum over its bonds of (-1/2 h_ij) g_ij (x) r0_ij in CSR
  // order, from g and r0 as the owner stored them (both change sign from
  // the other end: the same bits), then S_i A_i^-1 += Q_i A_i^-1.
  void gather_hourglass_stress(const BondTable& bonds, Range block) {
    const auto finish = [&](std::size_t i, const double* q) {
      double qa[4];
      tensor2::times_a_inv(q, &a_inv_[4 * i], qa);
      for (std::size_t c = 0; c < 4; ++c) stress_a_[c * particle_count() + i] += qa[c];
    };
    gather_lanes(
        slots_, block,
        [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t first) {
          Lanes q[4] = {};
          for (const std::ptrdiff_t shift : pattern.slot_shift) {
            const auto at = [&](Field f) {
              return load_lanes(slot_[f] + static_cast<std::ptrdiff_t>(m) + shift);
            };
            add_hourglass_terms(q, at(kHourglass), at(kGapX), at(kGapY), at(kR0x), at(kR0y));
          }
          for (std::size_t k = first; k < kLanes; ++k) {  // finish adds: new lanes only
            const double qk[4] = {q[0][k], q[1][k], q[2][k], q[3][k]};
            finish(m + k, qk);
          }
        },
        [&](std::size_t i) {
          double q[4] = {0, 0, 0, 0};
          for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
            const std::size_t s = slots_.entry_slot[b];
            add_hourglass_terms(q, slot_[kHourglass][s], slot_[kGapX][s], slot_[kGapY][s],
                                slot_[kR0x][s], slot_[kR0y][s]);
          }
          finish(i, q);
        });
  }

  // Q += (-1/2 h) g (x) r0 (T: double or Lanes).
  template <class T>
  static void add_hourglass_terms(T* q, T h, T gx, T gy, T r0x, T r0y) {
    const T half_h = -0.5 * h;
    q[0] += half_h * gx * r0x;
    q[1] += half_h * gx * r0y;
    q[2] += half_h * gy * r0x;
    q[3] += half_h * gy * r0y;
  }

  // gap slots for `count` bonds (i + m, j + m) into slots s + m; F rows of 4.
  static void gap_terms(std::size_t count, const double* __restrict xi, const double* __restrict yi,
                        const double* __restrict xj, const double* __restrict yj,
                        const double* __restrict fi, const double* __restrict fj,
                        const double* __restrict r0x, const double* __restrict r0y,
                        double* __restrict gx, double* __restrict gy) {
    for (std::size_t m = 0; m < count; ++m) {
      const double* a = fi + 4 * m;
      const double* b = fj + 4 * m;
      gx[m] = (xj[m] - xi[m]) - 0.5 * ((a[0] + b[0]) * r0x[m] + (a[1] + b[1]) * r0y[m]);
      gy[m] = (yj[m] - yi[m]) - 0.5 * ((a[2] + b[2]) * r0x[m] + (a[3] + b[3]) * r0y[m]);
    }
  }

  // One bond's stress term wl (s r0) (s = (S_i + S_j) A^-1, row-major) and
  // hourglass force h g, added to the owner's force or subtracted from the
  // other end's. T: double or Lanes.
  template <bool Owner, class T>
  static void add_bond_force(T& fx, T& fy, T s0, T s1, T s2, T s3, T wl, T r0x, T r0y, T h, T gx,
                             T gy) {
    add_force<Owner>(fx, fy, wl * (s0 * r0x + s1 * r0y), wl * (s2 * r0x + s3 * r0y), h * gx,
                     h * gy);
  }

  // fx += s, then fx += h g (the owner's terms), or both subtracted (the
  // other end's terms are the owner's negated). T: double or Lanes.
  template <bool Owner, class T>
  static void add_force(T& fx, T& fy, T sx, T sy, T hx, T hy) {
    if constexpr (Owner) {
      fx += sx;
      fy += sy;
      fx += hx;
      fy += hy;
    } else {
      fx -= sx;
      fy -= sy;
      fx -= hx;
      fy -= hy;
    }
  }

  double volume_;
  bool consistent_hourglass_ = false;
  std::vector<double> a_inv_;     // A_i^-1, 4 per particle
  std::vector<double> def_grad_;  // F_i, 4 per particle
  std::vector<double> stress_a_;  // (S_i + Q_i) A_i^-1 by component: c * particle_count() + i
  std::vector<double> jacobian_;  // J_i
  BondSlots slots_;
  // Per slot: constants (h_ij = alpha E_ij V (2 / n0) wl_ij) and the
  // hourglass gap. The terms of G, Q and the force are not stored: their
  // gathers compute them.
  enum Field : std::size_t { kR0x, kR0y, kWl, kHourglass, kGapX, kGapY, kFields };
  SlotArrays slot_;
};

}  // namespace mpsolid
