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
#include <type_traits>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_slots.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/half_angles.hpp"
#include "src/core/option_table.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
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
  // Its coefficients are per bond: a rank's partial ghost rows need nothing
  // else (docs/mpi.md), so `whole_rows` changes nothing.
  PaperModelT(const ParticleStore& p, const BondTable& bonds, const OptionValues& options, Range)
      : PaperModelT(p, bonds, options) {}
  PaperModelT(const ParticleStore& p, const BondTable& bonds, const OptionValues&)
      : volume_(bonds.geometry.volume), slots_(make_bond_slots(bonds)) {
    const EntryCoefficients c = entry_coefficients(p, bonds);
    slot_ = SlotArrays(kFields, slots_.slot_count());
    prefetch_ = kFields * slots_.slot_count() * sizeof(double) > kPrefetchAboveBytes;
    const auto fill = [&](Field f, const std::vector<double>& per_entry) {
      fill_slot_array(slots_, bonds, per_entry, slot_[f]);
    };
    fill(kR0x, bonds.r0x);
    fill(kR0y, bonds.r0y);
    fill(kStrainCoef, c.strain);
    fill(kSpringCoef, c.spring);
    for (std::size_t k = 0; k < slots_.slot_count(); ++k)  // the bits of V * coef in the old loop
      slot_[kPressureCoef][k] = volume_ * slot_[kStrainCoef][k];
    // Bonds between two walls once and for all (the slot pass skips them):
    // walls stay at x0 with theta = 0, whose half angles are exactly 1 and 0.
    const HalfAngle rest = half_angle(0.0);
    for (std::size_t i = 0; i < p.walls.end; ++i)
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        if (j <= i || j >= p.walls.end) continue;
        store_kinematics(slots_.entry_slot[b],
                         kinematics(p.x0[i], p.y0[i], rest.cos, rest.sin, p.x0[j], p.y0[j],
                                    rest.cos, rest.sin, bonds.r0x[b], bonds.r0y[b]));
      }
  }

  // The per-bond coefficients of every bond table entry (MODEL.md sections
  // 2.3-2.4), mu_ij the arithmetic mean of the two ends' mu:
  // strain (d / n0) w0_ij / |r0_ij|, spring k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2
  // (N/m). The same from both ends of a bond, so the model keeps one per slot.
  struct EntryCoefficients {
    std::vector<double> strain, spring;
  };
  static EntryCoefficients entry_coefficients(const ParticleStore& p, const BondTable& bonds) {
    const double d_over_n0 = kDim / number_density(bonds);
    const double volume = bonds.geometry.volume;
    EntryCoefficients c{std::vector<double>(bonds.entry_count()),
                        std::vector<double>(bonds.entry_count())};
    parallel_for(0, p.size(), [&](std::size_t i) {
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const double r0x = bonds.r0x[b], r0y = bonds.r0y[b];
        const double len = std::sqrt(r0x * r0x + r0y * r0y);
        const double w0 = bond_math::weight(len, bonds.geometry.re);
        const double mu_ij = 0.5 * (p.mu[i] + p.mu[j]);
        c.strain[b] = d_over_n0 * w0 / len;
        c.spring[b] = volume * d_over_n0 * 4.0 * mu_ij * w0 / (len * len);
      }
    });
    return c;
  }

  // Pass 1 with no halo (the whole state on this process).
  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
    NoHalo none;
    strain_pass(p, bonds, range, none);
  }

  // What the step's halos carry between ranks or threads
  // (src/solver/step.hpp; on one thread `halo` does nothing): before pass 1,
  // what the slots read of a partner's motion (position and half angles:
  // posted here, received once the slots between two particles of the range
  // are done); after it, the pressure the force pass reads (a partner's
  // strain is never read), left posted for the step to finish.
  template <class Halo>
  static void share_motion(ParticleStore& p, Halo& halo) {
    halo.post("motion", {field_of(p.x), field_of(p.y), field_of(p.half_cos), field_of(p.half_sin)});
  }
  // Pass 1: each bond's kinematics once (its owner's thread), then each
  // particle's strain and pressure from its bonds' slots. The slots computed
  // are those the particles of `range` read: first the bonds between two of
  // them, which read no ghost (on a part, while the motion halo travels),
  // then those with one end outside (on a part, a ghost): owned below
  // `range` and reaching into it, or owned in it and reaching above. Bonds
  // between two ghosts are never read.
  template <class Halo>
  void strain_pass(ParticleStore& p, const BondTable& bonds, Range range, Halo& halo) {
    const std::size_t n = p.size();
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      compute_bond_slots(p, {b, e}, range);
    });
    halo.finish();
    if (range.begin > 0)
      parallel_blocks(0, range.begin, [&](std::size_t b, std::size_t e) {
        compute_bond_slots(p, {b, e}, {range.begin, n});
      });
    if (range.end < n)
      parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
        compute_bond_slots(p, {b, e}, {range.end, n});
      });
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      gather_strain(p, bonds, {b, e});
    });
    halo.post("pressure", {field_of(p.pressure)});
  }

  // Pass 2 (needs pass 1 at the current state): force and torque.
  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      compute_forces_block(p, bonds, {b, e});
    });
  }

  // Whether the force gather prefetches (the slot data exceed kPrefetchAboveBytes).
  bool prefetches() const { return prefetch_; }

  // Pass 2 on one block, serially (the step fuses it with the integration).
  void compute_forces_block(ParticleStore& p, const BondTable& bonds, Range block) const {
    if (prefetch_)
      forces_block<true>(p, bonds, block);
    else
      forces_block<false>(p, bonds, block);
  }

  // Strain energy of particle i (MODEL.md section 4b): its share of
  // sum over bonds (each once) of 1/2 k_ij |u_ij|^2, plus 1/2 lambda_i V eps_i^2.
  // Reads the slots: needs the strain pass at the current state.
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    double bond_energy = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t s = slots_.entry_slot[b];
      bond_energy +=
          slot_[kSpringCoef][s] * (slot_[kUx][s] * slot_[kUx][s] + slot_[kUy][s] * slot_[kUy][s]);
    }
    // Each bond is seen from both ends: a quarter of k |u|^2 per end.
    return 0.25 * bond_energy + 0.5 * p.lambda[i] * volume_ * p.strain[i] * p.strain[i];
  }

  // A bond turned inside out: r_ij . R(theta_ij) r0_ij <= 0. Reports the bond
  // with the smallest cosine between r_ij and R(theta_ij) r0_ij (the same
  // from both ends) among the rows of `range`. Reads the slots: needs the
  // strain pass at the current state.
  IntegrityReport check_integrity(const ParticleStore&, const BondTable& bonds,
                                  const IntegrityLimits&, Range range) const {
    std::vector<double> worst(range.size());
    std::vector<std::size_t> partner(range.size());
    parallel_for(range.begin, range.end, [&](std::size_t i) {
      double lowest = 1.0;
      std::size_t at = i;
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t s = slots_.entry_slot[b];
        const double rx = slot_[kRx][s], ry = slot_[kRy][s];
        const double ax = rx - slot_[kUx][s], ay = ry - slot_[kUy][s];  // R(theta_ij) r0_ij
        const double cosine =
            (rx * ax + ry * ay) * slot_[kInvLen][s] / std::hypot(slot_[kR0x][s], slot_[kR0y][s]);
        if (cosine < lowest) {
          lowest = cosine;
          at = bonds.neighbor[b];
        }
      }
      worst[i - range.begin] = lowest;
      partner[i - range.begin] = at;
    });
    IntegrityReport r;
    if (range.empty()) return r;
    const std::size_t k = index_of_min(worst);
    r.particle = range.begin + k;
    r.neighbor = partner[k];
    r.value = worst[k];
    r.failed = !(r.value > 0.0);
    r.criterion = "bond turned inside out (r_ij . R(theta_ij) r0_ij <= 0)";
    return r;
  }

 private:
  // Pass 2 on one block (prefetching the slots' streams or not).
  template <bool Prefetch>
  void forces_block(ParticleStore& p, const BondTable& bonds, Range block) const {
    gather_lanes(
        slots_, block,
        [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t) {
          Lanes fx{}, fy{}, torque{};
          const Lanes pi = load_lanes(&p.pressure[m]);
          for (std::size_t k = 0; k < pattern.slot_shift.size(); ++k) {
            const std::size_t s = m + pattern.slot_shift[k];
            const auto at = [&](Field f) { return load_lanes_ahead<Prefetch>(slot_[f] + s); };
            const Lanes pj = load_lanes(&p.pressure[m + pattern.partner_shift[k]]);
            with_owner(pattern.partner_shift[k] > 0, [&](auto is_owner) {
              add_bond_force<is_owner()>(fx, fy, torque, pi, pj, at(kSpringCoef), at(kPressureCoef),
                                         at(kRx), at(kRy), at(kUx), at(kUy), at(kInvLen),
                                         EnergyConsistent ? at(kExtension) : Lanes{});
            });
          }
          store_lanes(&p.fx[m], fx);
          store_lanes(&p.fy[m], fy);
          store_lanes(&p.torque[m], 0.5 * torque);
        },
        [&](std::size_t i) {
          double fxi = 0.0, fyi = 0.0, ti = 0.0;
          for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
            const std::size_t j = bonds.neighbor[b], s = slots_.entry_slot[b];
            with_owner(j > i, [&](auto is_owner) {
              add_bond_force<is_owner()>(fxi, fyi, ti, p.pressure[i], p.pressure[j],
                                         slot_[kSpringCoef][s], slot_[kPressureCoef][s],
                                         slot_[kRx][s], slot_[kRy][s], slot_[kUx][s], slot_[kUy][s],
                                         slot_[kInvLen][s], extension_at(s));
            });
          }
          p.fx[i] = fxi;
          p.fy[i] = fyi;
          p.torque[i] = 0.5 * ti;
        });
  }

  // Pass 1a for the bonds owned by `owners`: the dense directions in unit
  // stride, the extra bonds (between bodies, and inside small ones) eight at
  // a time, with the same arithmetic. Bonds between two walls are skipped:
  // walls never move or turn (half angles exactly 1 and 0), so their slots
  // keep what the constructor put there, the bits this pass would compute.
  // Only bonds whose partner is in `partners` are computed.
  void compute_bond_slots(const ParticleStore& p, Range owners, Range partners) {
    const auto [first, last] = owned_extras(slots_, owners);
    const std::size_t fixed_end = p.walls.end;
    const auto wanted = [&](std::size_t j) {
      return j >= fixed_end && j >= partners.begin && j < partners.end;
    };
    const auto extra = [&](std::size_t k) {
      const std::size_t i = slots_.extra_owner[k], j = slots_.extra_partner[k];
      const std::size_t s = slots_.dense_slots + k;
      if (wanted(j))
        store_kinematics(s,
                         kinematics(p.x[i], p.y[i], p.half_cos[i], p.half_sin[i], p.x[j], p.y[j],
                                    p.half_cos[j], p.half_sin[j], slot_[kR0x][s], slot_[kR0y][s]));
    };
    // The values of kLanes particles listed at `at`.
    const auto ends = [](const std::vector<double>& a, const std::uint32_t* at) {
      double v[kLanes];
      for (std::size_t l = 0; l < kLanes; ++l) v[l] = a[at[l]];
      return load_lanes(v);
    };
    std::size_t k = first;
    for (; k + kLanes <= last; k += kLanes) {
      const std::uint32_t* owner = &slots_.extra_owner[k];
      const std::uint32_t* partner = &slots_.extra_partner[k];
      if (!std::all_of(partner, partner + kLanes, wanted)) {
        for (std::size_t l = k; l < k + kLanes; ++l) extra(l);
        continue;
      }
      const std::size_t s = slots_.dense_slots + k;
      store_kinematics(s,
                       kinematics(ends(p.x, owner), ends(p.y, owner), ends(p.half_cos, owner),
                                  ends(p.half_sin, owner), ends(p.x, partner), ends(p.y, partner),
                                  ends(p.half_cos, partner), ends(p.half_sin, partner),
                                  load_lanes(slot_[kR0x] + s), load_lanes(slot_[kR0y] + s)));
    }
    for (; k < last; ++k) extra(k);
    for_each_dense_slot(
        slots_, owners, fixed_end,
        [&](std::size_t count, std::size_t slot, std::size_t i, std::size_t j) {
          bond_kinematics(count, &p.x[i], &p.y[i], &p.half_cos[i], &p.half_sin[i], &p.x[j], &p.y[j],
                          &p.half_cos[j], &p.half_sin[j], &slot_[kR0x][slot], &slot_[kR0y][slot],
                          &slot_[kStrainCoef][slot], &slot_[kRx][slot], &slot_[kRy][slot],
                          &slot_[kUx][slot], &slot_[kUy][slot], &slot_[kInvLen][slot],
                          &slot_[kStrainTerm][slot],
                          EnergyConsistent ? &slot_[kExtension][slot] : nullptr);
        },
        partners);
  }

  // One bond's kinematics seen from its owner i: r_ij, u_ij, 1 / |r_ij| and
  // the normal extension u_ij . e_ij.
  // T: double, or Lanes (eight bonds, lane by lane).
  template <class T>
  struct Kinematics {
    T rx, ry, ux, uy, inv_len, extension;
  };
  template <class T>
  static Kinematics<T> kinematics(T xi, T yi, T ci, T si, T xj, T yj, T cj, T sj, T r0x, T r0y) {
    const auto rot = bond_math::bond_rotation(ci, si, cj, sj);
    const auto v = bond_math::bond_vectors(xi, yi, xj, yj, rot, r0x, r0y);
    const T il = 1.0 / lane_sqrt(v.rx * v.rx + v.ry * v.ry);
    return {v.rx, v.ry, v.ux, v.uy, il, bond_math::normal_extension(v, il)};
  }

  // Stores a bond's kinematics into slot s (T = double), or eight bonds'
  // into slots s .. s + kLanes - 1 (T = Lanes).
  template <class T>
  void store_kinematics(std::size_t s, const Kinematics<T>& k) {
    store_to(slot_[kRx] + s, k.rx);
    store_to(slot_[kRy] + s, k.ry);
    store_to(slot_[kUx] + s, k.ux);
    store_to(slot_[kUy] + s, k.uy);
    store_to(slot_[kInvLen] + s, k.inv_len);
    store_to(slot_[kStrainTerm] + s, load_as<T>(slot_[kStrainCoef] + s) * k.extension);
    if constexpr (EnergyConsistent) store_to(slot_[kExtension] + s, k.extension);
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
  void gather_strain(ParticleStore& p, const BondTable& bonds, Range block) const {
    const double* term = slot_[kStrainTerm];
    gather_lanes(
        slots_, block,
        [&](std::size_t m, const BondSlots::Pattern& pattern, std::size_t) {
          Lanes eps{};
          for (const std::ptrdiff_t shift : pattern.slot_shift)
            eps += load_lanes(term + static_cast<std::ptrdiff_t>(m) + shift);
          store_lanes(&p.strain[m], eps);
          store_lanes(&p.pressure[m], -load_lanes(&p.lambda[m]) * eps);
        },
        [&](std::size_t i) {
          double e = 0.0;
          for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b)
            e += term[slots_.entry_slot[b]];
          p.strain[i] = e;
          p.pressure[i] = -p.lambda[i] * e;
        });
  }

  // One bond's force and torque terms on one end i (pressures pi, pj),
  // added to fx, fy, torque. The owner's r_ij and u_ij are stored; the other
  // end's are their negatives, so its force terms are the owner's negated:
  // bit for bit what that end computed for itself before.
  // T: double, or Lanes (eight bonds of eight particles, lane by lane).
  template <bool Owner, class T>
  static void add_bond_force(T& fx, T& fy, T& torque, T pi, T pj, T k, T vc, T rx, T ry, T ux, T uy,
                             T inv_len, T extension) {
    const T c = vc * (pi + pj) * inv_len;
    const T tx = k * ux - c * rx;
    const T ty = k * uy - c * ry;
    if constexpr (Owner) {
      fx += tx;
      fy += ty;
    } else {
      fx -= tx;
      fy -= ty;
    }
    T bond_torque = k * bond_math::cross(rx, ry, ux, uy);
    if constexpr (EnergyConsistent) {
      // u^s = u - (u . e) e
      const T un = extension * inv_len;
      const T gx = c * (ux - un * rx);
      const T gy = c * (uy - un * ry);
      if constexpr (Owner) {
        fx -= gx;
        fy -= gy;
      } else {
        fx += gx;
        fy += gy;
      }
      bond_torque += c * bond_math::cross(ux, uy, rx, ry);
    }
    torque += bond_torque;
  }

  double extension_at(std::size_t s) const {
    if constexpr (EnergyConsistent) return slot_[kExtension][s];
    return 0.0;
  }

  // Calls f(std::true_type) or f(std::false_type): the owner's or the other
  // end's instance of a kernel, chosen once per call, inlined.
  template <class F>
  static void with_owner(bool owner, F&& f) {
    if (owner)
      f(std::true_type{});
    else
      f(std::false_type{});
  }

  double volume_ = 0;
  BondSlots slots_;
  bool prefetch_ = false;
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
