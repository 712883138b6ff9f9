#pragma once
// The paper's elastic MPS model (MODEL.md section 2), as two gather passes,
// and its energy-consistent variant (MODEL.md section 4b). Each bond's
// kinematics (r_ij, u_ij, 1 / |r_ij|, u_ij . e_ij) are computed once per step
// by its owner into its slot (kernels/bond_slots.hpp); both passes gather
// from the slots, each particle in its CSR order.
//
// Pass 1, strain and pressure, for every particle (walls and rigid included):
//   eps_i = (d / n0) sum_j w0_ij (u_ij . e_ij) / |r0_ij|,   p_i = -lambda_i eps_i
// Pass 2, fused force and torque, for the moving particles:
//   f_i   = sum_j k_ij u_ij  -  sum_j C_ij r_ij
//   tau_i = 1/2 sum_j k_ij (r_ij x u_ij)
// with k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (bond + shear stress of
// Eq. 5 fused: sigma^n + sigma^s = 2 mu u / |r0|), V = m / rho = l0^2 D, and
// C_ij = V (d / n0) w0_ij (p_i + p_j) / (|r0_ij| |r_ij|) (Eq. 5's pressure
// term with p_ij = (p_i + p_j) / 2). The torque is the paper's -T_ij / 2
// (Eq. 7): the normal part of u has no moment about r_ij, so r x u^s = r x u.
//
// Energy-consistent variant: the pressure force above is the gradient of
// sum_i 1/2 lambda_i V eps_i^2 only to first order; the missing part of the
// gradient adds, per bond, -C_ij u^s_ij to the force and
// 1/2 C_ij |r_ij| (u_ij x e_ij) = 1/2 C_ij (u_ij x r_ij) to the torque of
// each end.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/bond_loop.hpp"
#include "kernels/bond_slots.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/option_table.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

template <bool EnergyConsistent>
class PaperModelT {
 public:
  static constexpr const char* name = EnergyConsistent ? "paper_conservative" : "paper";
  static constexpr bool uses_rotation = true;
  static constexpr bool rotation_invariant = true;
  // The force pass reads the strain pass's slots and pressures, never a
  // position: a block's forces and integration need no barrier between them.
  static constexpr bool forces_read_positions = false;
  static constexpr const char* options_section = "";  // no options
  static std::vector<OptionSpec> options() { return {}; }

  PaperModelT() = default;  // no bonds: only a placeholder to assign a model to
  // The per-bond coefficients (MODEL.md sections 2.3-2.4), mu_ij the
  // arithmetic mean of the two ends' mu; per entry, and per slot (bond_slots.hpp).
  PaperModelT(const ParticleStore& p, const BondTable& bonds, const OptionValues&)
      : volume_(bonds.geometry.volume),
        slots_(make_bond_slots(bonds)),
        row_offsets_(bonds.offsets),
        neighbor_(bonds.neighbor) {
    const double d_over_n0 = kDim / number_density(bonds);
    strain_coef_.resize(bonds.entry_count());
    spring_coef_.resize(bonds.entry_count());
    parallel_for(0, p.size(), [&](std::size_t i) {
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
        const double len = std::sqrt(r0x * r0x + r0y * r0y);
        const double w0 = bond_math::weight(len, bonds.geometry.re);
        const double mu_ij = 0.5 * (p.mu[i] + p.mu[j]);
        strain_coef_[b] = d_over_n0 * w0 / len;
        spring_coef_[b] = volume_ * d_over_n0 * 4.0 * mu_ij * w0 / (len * len);
      }
    });
    slot_ = SlotArrays(kFields, slots_.slot_count());
    const auto fill = [&](Field f, const std::vector<double>& per_entry) {
      const std::vector<double> v = slot_values(slots_, bonds, per_entry);
      std::copy(v.begin(), v.end(), slot_[f]);
    };
    fill(kR0x, bonds.r0x);
    fill(kR0y, bonds.r0y);
    fill(kStrainCoef, strain_coef_);
    fill(kSpringCoef, spring_coef_);
    for (std::size_t k = 0; k < slots_.slot_count(); ++k)  // the bits of V * coef in the old loop
      slot_[kPressureCoef][k] = volume_ * slot_[kStrainCoef][k];
  }

  // Pass 1: each bond's kinematics once (its owner's thread), then each
  // particle's strain and pressure from its bonds' slots. Every particle's
  // slots are computed whatever `range` is.
  void compute_strain(ParticleStore& p, const BondTable&, Range range) {
    parallel_blocks(0, p.size(), [&](std::size_t b, std::size_t e) {
      compute_bond_slots(p, {b, e});
    });
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      gather_strain(p, {b, e});
    });
  }

  // Pass 2 (needs pass 1 at the current state): force and torque.
  void compute_forces(ParticleStore& p, const BondTable&, Range range) const {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      compute_forces_block(p, {b, e});
    });
  }

  // Pass 2 on one block, serially (the step fuses it with the integration).
  void compute_forces_block(ParticleStore& p, Range block) const {
    for_each_run(
        slots_, block,
        [&](std::size_t begin, std::size_t end, const BondSlots::Pattern& pattern) {
          for (std::size_t c0 = begin; c0 < end; c0 += kChunk) {
            const std::size_t count = std::min(kChunk, end - c0);
            double fx[kChunk] = {}, fy[kChunk] = {}, torque[kChunk] = {};
            for (std::size_t k = 0; k < pattern.slot_shift.size(); ++k) {
              const std::size_t s =
                  static_cast<std::size_t>(pattern.slot_shift[k] + static_cast<std::ptrdiff_t>(c0));
              const std::size_t j = static_cast<std::size_t>(pattern.partner_shift[k] +
                                                             static_cast<std::ptrdiff_t>(c0));
              if (pattern.partner_shift[k] > 0)
                add_bond_forces<true>(count, &p.pressure[c0], &p.pressure[j], s, fx, fy, torque);
              else
                add_bond_forces<false>(count, &p.pressure[c0], &p.pressure[j], s, fx, fy, torque);
            }
            for (std::size_t m = 0; m < count; ++m) {
              p.fx[c0 + m] = fx[m];
              p.fy[c0 + m] = fy[m];
              p.torque[c0 + m] = 0.5 * torque[m];
            }
          }
        },
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) {
            double fx = 0.0, fy = 0.0, torque = 0.0;
            for (std::uint32_t b = row_begin(i); b < row_begin(i + 1); ++b) {
              const std::size_t j = neighbor_[b], s = slots_.entry_slot[b];
              const double pi = p.pressure[i], pj = p.pressure[j];
              if (j > i)
                add_bond_force<true>(fx, fy, torque, pi, pj, slot_[kSpringCoef][s],
                                     slot_[kPressureCoef][s], slot_[kRx][s], slot_[kRy][s],
                                     slot_[kUx][s], slot_[kUy][s], slot_[kInvLen][s],
                                     extension_at(s));
              else
                add_bond_force<false>(fx, fy, torque, pi, pj, slot_[kSpringCoef][s],
                                      slot_[kPressureCoef][s], slot_[kRx][s], slot_[kRy][s],
                                      slot_[kUx][s], slot_[kUy][s], slot_[kInvLen][s],
                                      extension_at(s));
            }
            p.fx[i] = fx;
            p.fy[i] = fy;
            p.torque[i] = 0.5 * torque;
          }
        });
  }

  // Strain energy of particle i (MODEL.md section 4b): its share of
  // sum over bonds (each once) of 1/2 k_ij |u_ij|^2, plus 1/2 lambda_i V eps_i^2.
  // Needs the strain pass at the current state.
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    double bond_energy = 0.0;
    for_each_bond(p, bonds, i, [&](std::uint32_t b, std::size_t, const auto& v, double) {
      bond_energy += spring_coef_[b] * (v.ux * v.ux + v.uy * v.uy);
    });
    // Each bond is seen from both ends: a quarter of k |u|^2 per end.
    return 0.25 * bond_energy + 0.5 * p.lambda[i] * volume_ * p.strain[i] * p.strain[i];
  }

  // A bond turned inside out: r_ij . R(theta_ij) r0_ij <= 0. Reports the bond
  // with the smallest cosine between r_ij and R(theta_ij) r0_ij.
  IntegrityReport check_integrity(const ParticleStore& p, const BondTable& bonds,
                                  const IntegrityLimits&) const {
    std::vector<double> worst(p.size());
    std::vector<std::size_t> partner(p.size());
    parallel_for(0, p.size(), [&](std::size_t i) {
      double lowest = 1.0;
      std::size_t at = i;
      for_each_bond(
          p, bonds, i, [&](std::uint32_t b, std::size_t j, const auto& v, double inv_len) {
            const double ax = v.rx - v.ux, ay = v.ry - v.uy;  // R(theta_ij) r0_ij
            const double cosine =
                (v.rx * ax + v.ry * ay) * inv_len / std::hypot(bonds.r0x[b], bonds.r0y[b]);
            if (cosine < lowest) {
              lowest = cosine;
              at = j;
            }
          });
      worst[i] = lowest;
      partner[i] = at;
    });
    IntegrityReport r;
    if (p.size() == 0) return r;
    r.particle = index_of_min(worst);
    r.neighbor = partner[r.particle];
    r.value = worst[r.particle];
    r.failed = !(r.value > 0.0);
    r.criterion = "bond turned inside out (r_ij . R(theta_ij) r0_ij <= 0)";
    return r;
  }

  // (d / n0) w0_ij / |r0_ij| and k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (N/m) per bond entry.
  const std::vector<double>& strain_coefficients() const { return strain_coef_; }
  const std::vector<double>& spring_coefficients() const { return spring_coef_; }

 private:
  static constexpr std::size_t kChunk = 256;  // particles per gather chunk (accumulators in L1)

  std::uint32_t row_begin(std::size_t i) const { return row_offsets_[i]; }

  // Pass 1a for the bonds owned by `owners`: the dense directions in unit
  // stride, the few extra bonds one by one, with the same arithmetic.
  // Bonds between two walls are skipped: walls never move or turn (half
  // angles exactly 1 and 0), so their u_ij is exactly 0 and their strain
  // term a zero, which leaves every sum it would join unchanged (a sum that
  // starts at +0 only gains ±0 as +0 + ±0 = +0, and x + ±0 = x otherwise);
  // their slots keep the zeros they were made with, and no force pass reads
  // them (walls are not moving).
  void compute_bond_slots(const ParticleStore& p, Range owners) {
    for_each_owned_slot(
        slots_, owners, p.walls.end,
        [&](std::size_t count, std::size_t slot, std::size_t i, std::size_t j) {
          bond_kinematics(count, &p.x[i], &p.y[i], &p.half_cos[i], &p.half_sin[i], &p.x[j], &p.y[j],
                          &p.half_cos[j], &p.half_sin[j], &slot_[kR0x][slot], &slot_[kR0y][slot],
                          &slot_[kStrainCoef][slot], &slot_[kRx][slot], &slot_[kRy][slot],
                          &slot_[kUx][slot], &slot_[kUy][slot], &slot_[kInvLen][slot],
                          &slot_[kStrainTerm][slot],
                          EnergyConsistent ? &slot_[kExtension][slot] : nullptr);
        },
        [&](std::size_t s, std::size_t i, std::size_t j) {
          const Kinematics k =
              kinematics(p.x[i], p.y[i], p.half_cos[i], p.half_sin[i], p.x[j], p.y[j],
                         p.half_cos[j], p.half_sin[j], slot_[kR0x][s], slot_[kR0y][s]);
          slot_[kRx][s] = k.rx;
          slot_[kRy][s] = k.ry;
          slot_[kUx][s] = k.ux;
          slot_[kUy][s] = k.uy;
          slot_[kInvLen][s] = k.inv_len;
          slot_[kStrainTerm][s] = slot_[kStrainCoef][s] * k.extension;
          if constexpr (EnergyConsistent) slot_[kExtension][s] = k.extension;
        });
  }

  // One bond's kinematics seen from its owner i: r_ij, u_ij, 1 / |r_ij| and
  // the normal extension u_ij . e_ij.
  struct Kinematics {
    double rx, ry, ux, uy, inv_len, extension;
  };
  static Kinematics kinematics(double xi, double yi, double ci, double si, double xj, double yj,
                               double cj, double sj, double r0x, double r0y) {
    const auto rot = bond_math::bond_rotation(ci, si, cj, sj);
    const auto v = bond_math::bond_vectors(xi, yi, xj, yj, rot, r0x, r0y);
    const double il = 1.0 / std::sqrt(v.rx * v.rx + v.ry * v.ry);
    return {v.rx, v.ry, v.ux, v.uy, il, bond_math::normal_extension(v, il)};
  }

  // kinematics() for `count` bonds (i + m, j + m) into slots slot + m. Unit
  // stride and no aliasing (a static function of restrict pointers): GCC
  // vectorises it.
  static void bond_kinematics(std::size_t count, const double* __restrict xi,
                              const double* __restrict yi, const double* __restrict ci,
                              const double* __restrict si, const double* __restrict xj,
                              const double* __restrict yj, const double* __restrict cj,
                              const double* __restrict sj, const double* __restrict r0x,
                              const double* __restrict r0y, const double* __restrict coef,
                              double* __restrict rx, double* __restrict ry, double* __restrict ux,
                              double* __restrict uy, double* __restrict inv_len,
                              double* __restrict term, double* __restrict extension) {
    for (std::size_t m = 0; m < count; ++m) {
      const Kinematics k =
          kinematics(xi[m], yi[m], ci[m], si[m], xj[m], yj[m], cj[m], sj[m], r0x[m], r0y[m]);
      rx[m] = k.rx;
      ry[m] = k.ry;
      ux[m] = k.ux;
      uy[m] = k.uy;
      inv_len[m] = k.inv_len;
      term[m] = coef[m] * k.extension;
      if constexpr (EnergyConsistent) extension[m] = k.extension;
    }
  }

  // Pass 1b: eps_i = sum of its bonds' strain terms in CSR order.
  void gather_strain(ParticleStore& p, Range block) const {
    const double* term = slot_[kStrainTerm];
    for_each_run(
        slots_, block,
        [&](std::size_t begin, std::size_t end, const BondSlots::Pattern& pattern) {
          for (std::size_t c0 = begin; c0 < end; c0 += kChunk) {
            const std::size_t count = std::min(kChunk, end - c0);
            double eps[kChunk] = {};
            for (const std::ptrdiff_t shift : pattern.slot_shift) {
              const double* __restrict t = term + (shift + static_cast<std::ptrdiff_t>(c0));
              for (std::size_t m = 0; m < count; ++m) eps[m] += t[m];
            }
            for (std::size_t m = 0; m < count; ++m) {
              p.strain[c0 + m] = eps[m];
              p.pressure[c0 + m] = -p.lambda[c0 + m] * eps[m];
            }
          }
        },
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) {
            double eps = 0.0;
            for (std::uint32_t b = row_begin(i); b < row_begin(i + 1); ++b)
              eps += term[slots_.entry_slot[b]];
            p.strain[i] = eps;
            p.pressure[i] = -p.lambda[i] * eps;
          }
        });
  }

  // One bond's force and torque terms on one end i (pressures pi, pj),
  // added to fx, fy, torque. The owner's r_ij and u_ij are stored; the other
  // end's are their negatives, so its force terms are the owner's negated:
  // bit for bit what that end computed for itself before.
  template <bool Owner>
  static void add_bond_force(double& fx, double& fy, double& torque, double pi, double pj, double k,
                             double vc, double rx, double ry, double ux, double uy, double inv_len,
                             double extension) {
    const double c = vc * (pi + pj) * inv_len;
    const double tx = k * ux - c * rx;
    const double ty = k * uy - c * ry;
    fx = Owner ? fx + tx : fx - tx;
    fy = Owner ? fy + ty : fy - ty;
    double bond_torque = k * bond_math::cross(rx, ry, ux, uy);
    if constexpr (EnergyConsistent) {
      // u^s = u - (u . e) e
      const double un = extension * inv_len;
      const double gx = c * (ux - un * rx);
      const double gy = c * (uy - un * ry);
      fx = Owner ? fx - gx : fx + gx;
      fy = Owner ? fy - gy : fy + gy;
      bond_torque += c * bond_math::cross(ux, uy, rx, ry);
    }
    torque += bond_torque;
  }

  double extension_at(std::size_t s) const {
    if constexpr (EnergyConsistent) return slot_[kExtension][s];
    return 0.0;
  }

  // add_bond_force() for `count` bonds in slots slot + m on particles
  // i + m (pressures pi[m], partners' pj[m]), into fx, fy, torque[m].
  template <bool Owner>
  void add_bond_forces(std::size_t count, const double* pi, const double* pj, std::size_t slot,
                       double* fx, double* fy, double* torque) const {
    bond_forces<Owner>(count, pi, pj, &slot_[kSpringCoef][slot], &slot_[kPressureCoef][slot],
                       &slot_[kRx][slot], &slot_[kRy][slot], &slot_[kUx][slot], &slot_[kUy][slot],
                       &slot_[kInvLen][slot], EnergyConsistent ? &slot_[kExtension][slot] : nullptr,
                       fx, fy, torque);
  }

  template <bool Owner>
  static void bond_forces(std::size_t count, const double* __restrict pi,
                          const double* __restrict pj, const double* __restrict k,
                          const double* __restrict vc, const double* __restrict rx,
                          const double* __restrict ry, const double* __restrict ux,
                          const double* __restrict uy, const double* __restrict inv_len,
                          const double* __restrict extension, double* __restrict fx,
                          double* __restrict fy, double* __restrict torque) {
    for (std::size_t m = 0; m < count; ++m)
      add_bond_force<Owner>(fx[m], fy[m], torque[m], pi[m], pj[m], k[m], vc[m], rx[m], ry[m], ux[m],
                            uy[m], inv_len[m], EnergyConsistent ? extension[m] : 0.0);
  }

  double volume_ = 0;
  BondSlots slots_;
  std::vector<std::uint32_t> row_offsets_, neighbor_;  // the bond table's rows
  std::vector<double> strain_coef_, spring_coef_;      // per entry
  // Per slot: constants, then pass 1's kinematics (extension: the
  // energy-consistent variant only).
  enum Field : std::size_t {
    kR0x,
    kR0y,
    kStrainCoef,
    kSpringCoef,
    kPressureCoef,
    kRx,
    kRy,
    kUx,
    kUy,
    kInvLen,
    kStrainTerm,
    kExtension,
    kFields
  };
  SlotArrays slot_;
};

using PaperModel = PaperModelT<false>;
using PaperConservativeModel = PaperModelT<true>;

}  // namespace mpsolid
