#pragma once
// The paper's model (MODEL.md section 2) and its energy-consistent variant
// (section 4b) in space, as per-particle gathers with no per-bond array
// (as kernels/gradient_gather_model.hpp): each pass recomputes a bond's
// kinematics from the two ends' particle data.
//
// Each particle carries a unit quaternion q_i; a bond's reference vector is
// turned by the pair's mean rotation, normalize(q_i + s q_j) with s = +-1 so
// that q_i . (s q_j) >= 0 (the geodesic midpoint: symmetric in i and j, and
// for turns about one axis the turn by the mean angle, so a plane motion
// gives the plane model's u_ij):
//   u_ij = r_ij - R_ij r0_ij,  e_ij = r_ij / |r_ij|
// Pass 1, for every particle:
//   eps_i = (d / n0) sum_j w0_ij (u_ij . e_ij) / |r0_ij|,   p_i = -lambda_i eps_i
// Pass 2, for the moving particles (reads positions: integration waits):
//   f_i   = sum_j k_ij u_ij - sum_j C_ij r_ij
//   tau_i = 1/2 sum_j k_ij (r_ij x u_ij)
// k_ij = V (d / n0) 4 mu_ij w0_ij / |r0_ij|^2, C_ij = V (d / n0) w0_ij
// (p_i + p_j) / (|r0_ij| |r_ij|), V = l0^3, d = 3. The energy-consistent
// variant adds -C_ij u^s_ij to the force and 1/2 C_ij (u_ij x r_ij) to the
// torque. Every term is computed from both ends with the same operations on
// the pair's data (u, r, r0 change sign bit for bit, the mean rotation is
// the same rotation from either end), so the two ends' forces are exact
// negatives, and each particle sums in its row's order: the same bits at any
// thread and rank count.
#include <fmt/format.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "kernels/bond_math.hpp"
#include "kernels/bond_shells.hpp"
#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/option_table.hpp"
#include "src/core/parallel.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

template <bool EnergyConsistent>
class PaperGatherModel {
 public:
  using Vec = Eigen::Vector3d;
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
        shells_(find_bond_shells(p, bonds)) {
    for (const double len : shells_.length) shell_w0_.push_back(bond_math::weight(len, re_));
    if (p.dimension != 3)
      throw std::logic_error(fmt::format("{}: a 3D kernel for a {}D store", name, p.dimension));
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
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) gather_strain(p, bonds, i);
    });
    halo.post("pressure", {field_of(p.pressure)});  // the step finishes it
  }

  void compute_forces(ParticleStore& p, const BondTable& bonds, Range range) const {
    parallel_blocks(range.begin, range.end, [&](std::size_t b, std::size_t e) {
      for (std::size_t i = b; i < e; ++i) gather_force(p, bonds, i);
    });
  }

  // 1/4 sum_j k_ij |u_ij|^2 + 1/2 lambda_i V eps_i^2 (a current strain pass).
  double particle_strain_energy(const ParticleStore& p, const BondTable& bonds,
                                std::size_t i) const {
    double bond_energy = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const Bond k = bond(p, i, bonds.neighbor[b], b);
      bond_energy += spring(p, i, bonds.neighbor[b], k) * k.u.squaredNorm();
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
    for (std::size_t i = range.begin; i < range.end; ++i)
      for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
        const Bond k = bond(p, i, bonds.neighbor[b], b);
        const Vec turned = k.r - k.u;  // R_ij r0_ij
        const double cosine = k.r.dot(turned) / (k.length * k.r0_length);
        if (cosine < r.value) {
          r.value = cosine;
          r.particle = i;
          r.neighbor = bonds.neighbor[b];
        }
      }
    r.failed = !(r.value > 0.0);
    r.criterion = "bond turned inside out (cos(r_ij, R_ij r0_ij) <= 0)";
    return r;
  }

 private:
  struct Bond {
    Vec r, u;
    double length, r0_length, w0;
  };

  static Vec at(const double* x, const double* y, const double* z, std::size_t i) {
    return {x[i], y[i], z[i]};
  }
  static Eigen::Quaterniond orientation(const ParticleStore& p, std::size_t i) {
    return {p.qw[i], p.qx[i], p.qy[i], p.qz[i]};
  }
  // Entry b of row i, j its partner.
  Bond bond(const ParticleStore& p, std::size_t i, std::size_t j, std::uint32_t b) const {
    Bond k;
    const Vec r0 =
        at(p.x0.data(), p.y0.data(), p.z0.data(), j) - at(p.x0.data(), p.y0.data(), p.z0.data(), i);
    k.r = at(p.x.data(), p.y.data(), p.z.data(), j) - at(p.x.data(), p.y.data(), p.z.data(), i);
    k.u = k.r - bond_math::mean_rotation(orientation(p, i), orientation(p, j)) * r0;
    k.length = k.r.norm();
    if (const std::uint8_t shell = shells_.of_entry[b]; shell != BondShells::kOff) {
      k.r0_length = shells_.length[shell];
      k.w0 = shell_w0_[shell];
    } else {
      k.r0_length = std::sqrt(reference_length2(p, i, j));
      k.w0 = bond_math::weight(k.r0_length, re_);
    }
    return k;
  }
  // k_ij, mu_ij the ends' mean.
  double spring(const ParticleStore& p, std::size_t i, std::size_t j, const Bond& k) const {
    return volume_ * d_over_n0_ * 4.0 * (0.5 * (p.mu[i] + p.mu[j])) * k.w0 /
           (k.r0_length * k.r0_length);
  }

  void gather_strain(ParticleStore& p, const BondTable& bonds, std::size_t i) const {
    double sum = 0.0;
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const Bond k = bond(p, i, bonds.neighbor[b], b);
      sum += k.w0 * (k.u.dot(k.r) / k.length) / k.r0_length;
    }
    p.strain[i] = d_over_n0_ * sum;
    p.pressure[i] = -p.lambda[i] * p.strain[i];
  }

  void gather_force(ParticleStore& p, const BondTable& bonds, std::size_t i) const {
    Vec f = Vec::Zero(), torque = Vec::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Bond k = bond(p, i, j, b);
      const double spring_ij = spring(p, i, j, k);
      const double c =
          volume_ * d_over_n0_ * k.w0 * (p.pressure[i] + p.pressure[j]) / (k.r0_length * k.length);
      f += spring_ij * k.u;
      f -= c * k.r;
      torque += 0.5 * spring_ij * k.r.cross(k.u);
      if constexpr (EnergyConsistent) {
        const Vec unit = k.r / k.length;
        f -= c * (k.u - k.u.dot(unit) * unit);
        torque += 0.5 * c * k.u.cross(k.r);
      }
    }
    p.fx[i] = f[0];
    p.fy[i] = f[1];
    p.fz[i] = f[2];
    p.torque_x[i] = torque[0];
    p.torque_y[i] = torque[1];
    p.torque[i] = torque[2];
  }

  double volume_, re_, d_over_n0_;
  BondShells shells_;
  std::vector<double> shell_w0_;  // w0 of each shell
};

}  // namespace mpsolid
