#pragma once
// The largest stable step of symplectic Euler for a bond model: dt < 2 /
// omega_max, with omega_max^2 the largest eigenvalue of M^-1 K, K the
// stiffness of the linearised system about the current state (translations
// and, for models with rotation, particle spins; M holds masses and moments
// of inertia).
//
// omega_max comes from power iteration on the mass-weighted stiffness
// M^-1/2 K M^-1/2. Each product K v is a central difference of the model's
// own strain and force passes, so every model is covered by the same code and
// no hand-derived formula can drift from the kernels. Only elastic particles
// move in the iteration: walls never move, and a rigid body is far heavier
// than one particle, so its modes are slow.
//
// It runs where the step runs (a `Place`, src/solver/step.hpp): on the whole
// state, or on each rank's part with the ghosts' perturbed positions from
// the step's own halos. Its norms are ordered sums over the elastic
// particles (`Sums`: EstimateSums below, or a rank's share of them,
// src/solver/time_step_choice.cpp), so the estimate is the same bits at any
// thread and rank count.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "src/core/half_angles.hpp"
#include "src/core/integrator.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/stable_step_estimate.hpp"
#include "src/solver/step.hpp"

namespace mpsolid {

// The sums of an estimate on the whole state: its elastic particles, summed
// in ordered_sum's chunks.
struct EstimateSums {
  Range elastic;  // the particles the iteration moves (indices of the state)
  template <class Term>
  double sum(Term&& term) const {
    return ordered_sum<1>(elastic.begin, elastic.end,
                          [&](std::size_t i) { return std::array<double, 1>{term(i)}; })[0];
  }
  double largest(double mine) const { return mine; }
};

namespace detail {
// A particle's components in the iteration: its translations, then (models
// with rotation) its rotations: theta in the plane, a rotation vector in
// space.
struct Components {
  std::size_t translations, rotations;
  std::size_t count() const { return translations + rotations; }
};
inline Components components(const ParticleStore& p, bool rotation) {
  const std::size_t d = p.dimension == 3 ? 3 : 2;
  const std::size_t rotations = rotation ? (d == 3 ? 3 : 1) : 0;
  return {d, rotations};
}

// Sets `work`'s orientation of particle i to base's turned by `phi` (a
// rotation vector, rad): theta + phi in the plane, exp(phi / 2) q in space.
inline void turn(const ParticleStore& base, ParticleStore& work, std::size_t i, const double* phi) {
  if (base.dimension != 3) {
    work.theta[i] = base.theta[i] + phi[0];
    return;
  }
  const Eigen::Quaterniond q =
      turned(Eigen::Quaterniond(base.qw[i], base.qx[i], base.qy[i], base.qz[i]),
             Eigen::Vector3d(phi[0], phi[1], phi[2]));
  work.qw[i] = q.w();
  work.qx[i] = q.x();
  work.qy[i] = q.y();
  work.qz[i] = q.z();
}

// The place's forces and torques of the positions and orientations in
// `work`: the step's strain fields (half angles, halos, strain pass), then
// the force pass over its moving particles.
template <class Model, class Place>
void forces_of(Model& model, ParticleStore& work, const BondTable& bonds, Place& place) {
  strain_fields(model, work, bonds, place);
  model.compute_forces(work, bonds, own_moving(place, work));
}

// y = A u for the mass-weighted stiffness A about the state `base`; `work` is
// a scratch copy of it. u and y hold the sums' elastic particles' components.
template <class Model, class Place, class Sums>
void mass_weighted_stiffness(Model& model, const ParticleStore& base, ParticleStore& work,
                             const BondTable& bonds, double l0, Place& place, const Sums& sums,
                             const std::vector<double>& u, std::vector<double>& y) {
  constexpr bool rot = Model::uses_rotation;
  const Components comp = components(base, rot);
  const std::size_t c = comp.count(), nt = comp.translations;
  const Range r = sums.elastic;
  // Displacements d = M^-1/2 u, scaled so the largest moves l0 * 1e-7: small
  // enough to stay linear, large enough to keep 8 digits of the difference.
  double largest = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    const std::size_t i = r.begin + k;
    for (std::size_t a = 0; a < nt; ++a)
      largest = std::max(largest, std::abs(u[c * k + a]) * std::sqrt(base.inv_mass[i]));
    for (std::size_t a = nt; a < c; ++a)
      largest = std::max(largest, std::abs(u[c * k + a]) * std::sqrt(base.inv_inertia[i]) * l0);
  }
  const double h = 1e-7 * l0 / sums.largest(largest);
  std::vector<double> forces_plus(c * r.size());
  std::vector<double>* positions[3] = {&work.x, &work.y, &work.z};
  const std::vector<double>* base_positions[3] = {&base.x, &base.y, &base.z};
  const std::vector<double>* forces[3] = {&work.fx, &work.fy, &work.fz};
  // Torques: theta's in the plane; about x, y, z in space.
  const std::vector<double>* torques[3] = {&work.torque_x, &work.torque_y, &work.torque};
  const std::size_t first_torque = comp.rotations == 1 ? 2 : 0;
  for (const double sign : {1.0, -1.0}) {
    for (std::size_t k = 0; k < r.size(); ++k) {
      const std::size_t i = r.begin + k;
      for (std::size_t a = 0; a < nt; ++a)
        (*positions[a])[i] =
            (*base_positions[a])[i] + sign * h * u[c * k + a] * std::sqrt(base.inv_mass[i]);
      if (rot) {
        double phi[3];
        for (std::size_t a = 0; a < comp.rotations; ++a)
          phi[a] = sign * h * u[c * k + nt + a] * std::sqrt(base.inv_inertia[i]);
        turn(base, work, i, phi);
      }
    }
    forces_of(model, work, bonds, place);
    for (std::size_t k = 0; k < r.size(); ++k) {
      const std::size_t i = r.begin + k;
      for (std::size_t a = 0; a < c; ++a) {
        const double f = a < nt ? (*forces[a])[i] : (*torques[first_torque + a - nt])[i];
        if (sign > 0) {
          forces_plus[c * k + a] = f;
          continue;
        }
        const double scale = a < nt ? std::sqrt(base.inv_mass[i]) : std::sqrt(base.inv_inertia[i]);
        // K d = -dF/dd, so A u = -M^-1/2 (F(+h d) - F(-h d)) / (2 h).
        y[c * k + a] = -scale * (forces_plus[c * k + a] - f) / (2.0 * h);
      }
    }
  }
}

// |v| over every place's particles: each particle's components' squares
// summed in order, the particles in the sums' order.
template <class Sums>
double norm(const std::vector<double>& v, std::size_t c, const Sums& sums) {
  const std::size_t first = sums.elastic.begin;
  return std::sqrt(sums.sum([&](std::size_t i) {
    double s = 0;
    for (std::size_t a = 0; a < c; ++a) s += v[c * (i - first) + a] * v[c * (i - first) + a];
    return s;
  }));
}
}  // namespace detail

// omega_max and 2 / omega_max for the state `base` (usually the initial one)
// at `place`, whose own elastic particles are sums.elastic. Every rank of a
// place over ranks calls it and gets the same estimate. Deterministic: a
// fixed start vector and ordered sums, so the step is the same at any
// thread and rank count.
template <class Model, class Place, class Sums>
StableStepEstimate estimate_stable_step(Model& model, const ParticleStore& base,
                                        const BondTable& bonds, double l0, Place& place,
                                        const Sums& sums, int max_iterations = 2000,
                                        double tolerance = 1e-3) {
  const detail::Components comp = detail::components(base, Model::uses_rotation);
  const std::size_t c = comp.count(), nt = comp.translations;
  const Range r = sums.elastic;
  StableStepEstimate out;
  if (!(sums.largest(r.empty() ? 0.0 : 1.0) > 0)) return out;  // no elastic particle anywhere
  ParticleStore work = base;
  // Start near the stiffest lattice mode (neighbours moving against each
  // other), with a hashed component so no mode is missed by symmetry.
  std::vector<double> u(c * r.size()), y(c * r.size());
  for (std::size_t k = 0; k < r.size(); ++k) {
    const std::size_t i = r.begin + k;
    const auto kx = static_cast<std::int64_t>(std::floor(base.x0[i] / l0));
    const auto ky = static_cast<std::int64_t>(std::floor(base.y0[i] / l0));
    const auto kz =
        nt == 3 ? static_cast<std::int64_t>(std::floor(base.z0[i] / l0)) : std::int64_t{0};
    const double sign = ((kx + ky + kz) & 1) ? -1.0 : 1.0;
    const auto hash = static_cast<std::uint32_t>(base.id[i]) * 2654435761u;
    const double jitter = 0.1 * (static_cast<double>(hash >> 8) / 16777216.0 - 0.5);
    u[c * k] = (sign + jitter) / std::sqrt(base.inv_mass[i]);
    u[c * k + 1] = (((kx & 1) ? -sign : sign) - jitter) / std::sqrt(base.inv_mass[i]);
    if (nt == 3) u[c * k + 2] = (((ky & 1) ? -sign : sign) + jitter) / std::sqrt(base.inv_mass[i]);
    // Rotations: the same pattern, turned about each axis in turn.
    for (std::size_t a = nt; a < c; ++a)
      u[c * k + a] = ((a == nt ? sign : -sign) + jitter) / (l0 * std::sqrt(base.inv_inertia[i]));
  }
  // The top of a lattice's spectrum is dense, so the estimate creeps up: it
  // counts as converged when it grew by less than `tolerance` (relative) over
  // the last kWindow iterations.
  constexpr int kWindow = 50;
  std::vector<double> history;
  double length = detail::norm(u, c, sums);
  for (int it = 1; it <= max_iterations; ++it) {
    for (double& x : u) x /= length;
    detail::mass_weighted_stiffness(model, base, work, bonds, l0, place, sums, u, y);
    // |A u| with |u| = 1 rises to the largest |eigenvalue| from below.
    const double estimate = detail::norm(y, c, sums);
    history.push_back(estimate);
    out.iterations = it;
    out.omega_max = std::sqrt(estimate);
    u.swap(y);
    length = estimate;  // the next u's norm
    if (it > kWindow && estimate - history[it - 1 - kWindow] <= tolerance * estimate) {
      out.converged = true;
      break;
    }
  }
  out.dt_limit = out.omega_max > 0 ? 2.0 / out.omega_max : 0.0;
  return out;
}

}  // namespace mpsolid
