#pragma once
// The paper's model (MODEL.md section 2) and its energy-consistent variant
// (section 4b) in space, as per-particle gathers with no per-bond array
// (as kernels/gradient_gather_model.hpp): each pass recomputes a bond's
// kinematics from the two ends' particle data.
//
// Each particle carries a unit quaternion q_i; a bond's reference vector is
// turned by the pair's mean rotation, the rotation of q = q_i + s q_j with
// s = +-1 so that q_i . (s q_j) >= 0 (the geodesic midpoint: symmetric in i
// and j, and for turns about one axis the turn by the mean angle, so a plane
// motion gives the plane model's u_ij). q is not normalised: with v its
// vector part, R r0 = r0 + (2 / |q|^2) (w (v x r0) + v x (v x r0)).
//   u_ij = r_ij - R_ij r0_ij
// Pass 1, for every particle:
//   eps_i = (d / n0) sum_j w0_ij (u_ij . r_ij) / (|r_ij| |r0_ij|),   p_i = -lambda_i eps_i
// Pass 2, for the moving particles (reads positions: integration waits):
//   f_i   = sum_j a_ij u_ij - b_ij r_ij
//   tau_i = 1/2 sum_j a_ij (r_ij x u_ij)
// with k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2 (mu_ij the ends' mean) and
// C_ij = V (d / n0) w0_ij (p_i + p_j) / (|r0_ij| |r_ij|), V = l0^3, d = 3:
// the paper's model has a = k, b = C; the energy-consistent variant adds
// -C u^s_ij (u^s = u - (u . e) e, e = r / |r|) to the force and
// 1/2 C (u_ij x r_ij) to the torque, which is a = k - C,
// b = C (r_ij . R r0_ij) / |r_ij|^2.
//
// Every term is computed from both ends with the same operations on the
// pair's data (u, r, r0 change sign bit for bit, q is the same or its exact
// negative), so the two ends' forces are exact negatives, and each particle
// sums in its row's order: the same bits at any thread and rank count.
// Along a lattice line whose rows look alike (kernels/row_patterns.hpp) the
// passes take kLanes particles at a time with the same operations lane by
// lane: the same bits as row by row.
#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_shells.hpp"
#include "kernels/lanes.hpp"
#include "kernels/model_common.hpp"
#include "kernels/row_patterns.hpp"
#include "src/core/bonds.hpp"
#include "src/core/option_table.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

// One bond seen from end i: r_ij, u_ij and |r_ij|, for one particle
// (T = double) or kLanes (T = Lanes).
template <class T>
struct PaperBond3 {
  T r[3], u[3], length;
};

// End i's position, reference position and orientation.
template <class T>
struct PaperEnd3 {
  T x[3], x0[3], q[4];
};

// Particle i's (or kLanes particles' at i: load_at).
template <class T, class J>
PaperEnd3<T> paper_end3(const ParticleStore& p, J i) {
  const auto at = [&](const std::vector<double>& a) { return load_at<T>(a.data(), i); };
  return {{at(p.x), at(p.y), at(p.z)},
          {at(p.x0), at(p.y0), at(p.z0)},
          {at(p.qw), at(p.qx), at(p.qy), at(p.qz)}};
}

// The bond from end i (its data `a`) to partner j.
template <class T, class J>
PaperBond3<T> paper_bond3(const ParticleStore& p, const PaperEnd3<T>& a, J j) {
  const PaperEnd3<T> b = paper_end3<T>(p, j);
  const T dot = a.q[0] * b.q[0] + a.q[1] * b.q[1] + a.q[2] * b.q[2] + a.q[3] * b.q[3];
  const T side = lane_sign(dot);
  const T w = a.q[0] + side * b.q[0];
  const T v[3] = {a.q[1] + side * b.q[1], a.q[2] + side * b.q[2], a.q[3] + side * b.q[3]};
  const T twice_inv_norm2 = 2.0 / (w * w + v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const T r0[3] = {b.x0[0] - a.x0[0], b.x0[1] - a.x0[1], b.x0[2] - a.x0[2]};
  const T c[3] = {v[1] * r0[2] - v[2] * r0[1], v[2] * r0[0] - v[0] * r0[2],
                  v[0] * r0[1] - v[1] * r0[0]};  // v x r0
  const T cc[3] = {v[1] * c[2] - v[2] * c[1], v[2] * c[0] - v[0] * c[2],
                   v[0] * c[1] - v[1] * c[0]};  // v x (v x r0)
  PaperBond3<T> k;
  for (int d = 0; d < 3; ++d) {
    k.r[d] = b.x[d] - a.x[d];
    k.u[d] = k.r[d] - (r0[d] + twice_inv_norm2 * (w * c[d] + cc[d]));
  }
  k.length = lane_sqrt(k.r[0] * k.r[0] + k.r[1] * k.r[1] + k.r[2] * k.r[2]);
  return k;
}

template <bool EnergyConsistent>
class PaperGatherModel {
 public:
  static constexpr int dimension = 3;
  static constexpr const char* name = EnergyConsistent ? "paper_conservative" : "paper";
  static constexpr bool uses_rotation = true;
  static constexpr bool rotation_invariant = true;
  static constexpr bool forces_read_positions = true;
  static constexpr const char* options_section = "";  // no options
  static std::vector<OptionSpec> options() { return {}; }

  PaperGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues& options)
      : PaperGatherModel(p, bonds, options, p.all()) {}
  // Its coefficients are per bond, from the two ends: a rank's partial ghost
  // rows need nothing else, so `whole_rows` changes nothing.
  PaperGatherModel(const ParticleStore& p, const BondTable& bonds, const OptionValues&, Range)
      : volume_(bonds.geometry.volume),
        re_(bonds.geometry.re),
        d_over_n0_(3.0 / number_density(bonds)),
        shells_(find_bond_shells(p, bonds)),
        rows_(find_row_patterns(bonds, shells_.of_entry, BondShells::kOff)) {
    if (p.dimension != 3)
      throw std::logic_error(fmt::format("{}: a 3D kernel for a {}D store", name, p.dimension));
    for (const double len : shells_.length) shell_constants_.push_back(constants(len));
  }

  void compute_strain(ParticleStore& p, const BondTable& bonds, Range range) {
    NoHalo none;
    strain_pass(p, bonds, range, none);
  }

  // What the halos carry: before pass 1 a partner's position and
  // orientation, after it its pressure (left posted for the step).
  template <class Halo>
  static void share_motion(ParticleStore& p, Halo& halo) {
    halo.post("motion", {field_of(p.x), field_of(p.y), field_of(p.z), field_of(p.qw),
                         field_of(p.qx), field_of(p.qy), field_of(p.qz)});
  }
  template <class Halo>
  void strain_pass(ParticleStore& p, const BondTable& bonds, Range range, Halo& halo) {
    halo.finish();
    gather_range(rows_, bonds, shells_.of_entry, range,
                 [&](auto tag, std::size_t i, std::size_t count, auto&& entry, auto&& keep,
                     FreshLanes) { gather_strain<decltype(tag)>(p, i, count, entry, keep); });
    halo.post("pressure", {field_of(p.pressure)});  // the step finishes it
  }

  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    gather_range(rows_, bonds, shells_.of_entry, range,
                 [&](auto tag, std::size_t i, std::size_t count, auto&& entry, auto&& keep,
                     FreshLanes) { gather_force<decltype(tag)>(p, i, count, entry, keep); });
  }

  // Each particle row by row, as where no pattern fits (the tests' check
  // that both paths give the same bits).
  void take_rows_one_by_one() { rows_ = row_by_row(rows_.present.size()); }

  // 1/4 sum_j k_ij |u_ij|^2 + 1/2 lambda_i V eps_i^2 (a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    double bond_energy = 0.0;
    const PaperEnd3<double> a = paper_end3<double>(p, i);
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const auto e = resolve(p, i, {bonds.neighbor[b], shells_.of_entry[b]});
      const PaperBond3<double> k = paper_bond3<double>(p, a, e.partner);
      const double u2 = k.u[0] * k.u[0] + k.u[1] * k.u[1] + k.u[2] * k.u[2];
      bond_energy += e.spring * (p.mu[i] + p.mu[e.partner]) * u2;
    }
    return 0.25 * bond_energy + 0.5 * p.lambda[i] * volume_ * p.strain[i] * p.strain[i];
  }

  // A bond turned inside out: r_ij . R_ij r0_ij <= 0; the smallest cosine
  // between them among the rows of `range`.
  IntegrityReport check_integrity(const ParticleStore& p, const BondTable& bonds,
                                  const IntegrityLimits&, Range range) const {
    IntegrityReport r;
    if (range.empty()) return r;
    r.value = 1.0;
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const PaperEnd3<double> a = paper_end3<double>(p, i);
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const std::size_t j = bonds.neighbor[b];
        const PaperBond3<double> k = paper_bond3<double>(p, a, j);
        double r_dot_turned = 0.0;  // r . R r0, |R r0| = |r0|
        for (int d = 0; d < 3; ++d) r_dot_turned += k.r[d] * (k.r[d] - k.u[d]);
        const double cosine = r_dot_turned / (k.length * std::sqrt(reference_length2(p, i, j)));
        if (cosine < r.value) {
          r.value = cosine;
          r.particle = i;
          r.neighbor = j;
        }
      }
    }
    r.failed = !(r.value > 0.0);
    r.criterion = "bond turned inside out (cos(r_ij, R_ij r0_ij) <= 0)";
    return r;
  }

 private:
  // A bond's constants from its reference length.
  struct Constants {
    double strain;    // (d / n0) w0 / |r0|: eps_i's term over (u . r) / |r|
    double spring;    // V (d / n0) 2 w0 / |r0|^2: k_ij over (mu_i + mu_j)
    double pressure;  // V (d / n0) w0 / |r0|: C_ij over (p_i + p_j) / |r|
  };
  // An entry's partner (J: an index, or LaneInts) and constants (C: double,
  // or Lanes where each lane has its own).
  template <class C, class J>
  struct Entry {
    J partner;
    C strain, spring, pressure;
  };

  Constants constants(double r0_length) const {
    const double w0 = bond_math::weight(r0_length, re_);
    return {d_over_n0_ * w0 / r0_length, volume_ * d_over_n0_ * 2.0 * w0 / (r0_length * r0_length),
            volume_ * d_over_n0_ * w0 / r0_length};
  }
  // An entry of particle i's row: its shell's constants, or computed off
  // the shells.
  Constants constants(const ParticleStore& p, std::size_t i, std::size_t j,
                      std::int64_t shell) const {
    if (shell >= 0 && static_cast<std::size_t>(shell) < shell_constants_.size())
      return shell_constants_[static_cast<std::size_t>(shell)];
    return constants(std::sqrt(reference_length2(p, i, j)));
  }
  Entry<double, std::size_t> resolve(const ParticleStore& p, std::size_t i, RowEntry e) const {
    const Constants c = constants(p, i, e.partner, e.shell);
    return {e.partner, c.strain, c.spring, c.pressure};
  }
  Entry<Lanes, LaneInts> resolve(const ParticleStore& p, std::size_t i, const LaneEntry& e) const {
    Entry<Lanes, LaneInts> out;
    out.partner = e.partner;
    for (std::size_t l = 0; l < kLanes; ++l) {
      const Constants c = constants(p, i + l, static_cast<std::size_t>(e.partner[l]), e.shell[l]);
      out.strain[l] = c.strain;
      out.spring[l] = c.spring;
      out.pressure[l] = c.pressure;
    }
    return out;
  }

  // Pass 1 for particle i or kLanes from i, over its `count` entries.
  template <class T, class Entries, class Keep>
  void gather_strain(ParticleStore& p, std::size_t i, std::size_t count, Entries&& entries,
                     Keep&& keep) const {
    const PaperEnd3<T> a = paper_end3<T>(p, i);
    T eps{};
    for (std::size_t n = 0; n < count; ++n) {
      const auto e = resolve(p, i, entries(n));
      const PaperBond3<T> k = paper_bond3<T>(p, a, e.partner);
      eps += keep(n, e.strain * ((k.u[0] * k.r[0] + k.u[1] * k.r[1] + k.u[2] * k.r[2]) / k.length));
    }
    store_to(&p.strain[i], eps);
    store_to(&p.pressure[i], -load_as<T>(&p.lambda[i]) * eps);
  }

  // Pass 2 for particle i or kLanes from i.
  // A masked entry's terms are selected away (kernels/row_patterns.hpp),
  // whatever its partner holds.
  template <class T, class Entries, class Keep>
  void gather_force(ParticleStore& p, std::size_t i, std::size_t count, Entries&& entries,
                    Keep&& keep) const {
    const PaperEnd3<T> a = paper_end3<T>(p, i);
    const T mu = load_as<T>(&p.mu[i]), pressure = load_as<T>(&p.pressure[i]);
    T f[3] = {}, torque[3] = {};
    for (std::size_t n = 0; n < count; ++n) {
      const auto e = resolve(p, i, entries(n));
      const PaperBond3<T> k = paper_bond3<T>(p, a, e.partner);
      const T spring = e.spring * (mu + load_at<T>(p.mu.data(), e.partner));
      const T inv_length = 1.0 / k.length;
      const T c = e.pressure * (pressure + load_at<T>(p.pressure.data(), e.partner)) * inv_length;
      T along = spring, across = c;  // a_ij, b_ij
      if constexpr (EnergyConsistent) {
        const T turned_r = k.r[0] * (k.r[0] - k.u[0]) + k.r[1] * (k.r[1] - k.u[1]) +
                           k.r[2] * (k.r[2] - k.u[2]);  // r . R r0
        along = spring - c;
        across = c * (turned_r * inv_length * inv_length);
      }
      for (int d = 0; d < 3; ++d) f[d] += keep(n, along * k.u[d] - across * k.r[d]);
      torque[0] += keep(n, along * (k.r[1] * k.u[2] - k.r[2] * k.u[1]));
      torque[1] += keep(n, along * (k.r[2] * k.u[0] - k.r[0] * k.u[2]));
      torque[2] += keep(n, along * (k.r[0] * k.u[1] - k.r[1] * k.u[0]));
    }
    store_to(&p.fx[i], f[0]);
    store_to(&p.fy[i], f[1]);
    store_to(&p.fz[i], f[2]);
    store_to(&p.torque_x[i], 0.5 * torque[0]);
    store_to(&p.torque_y[i], 0.5 * torque[1]);
    store_to(&p.torque[i], 0.5 * torque[2]);
  }

  double volume_, re_, d_over_n0_;
  BondShells shells_;
  RowPatterns rows_;
  std::vector<Constants> shell_constants_;  // of each shell
};

}  // namespace mpsolid
