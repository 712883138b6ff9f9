#pragma once
// The decomposed step on one rank (docs/mpi.md), for every model: the
// rank steps its own particles on its local state, and before each pass
// that reads neighbours its ghosts get their owners' values (the halos).
// Every owned particle then computes exactly what the serial step computes,
// in the same order: the same bits at any rank count.
//
// Halos per step, the paper models: positions, rotations and half angles
// before the strain pass; strain and pressure before the force pass. The
// corrected-gradient models: positions; F after pass 1 (a bond's gap reads
// both ends'); (S + Q) A^-1 before the force pass. (A ghost's A^-1, which
// its partial local row cannot give, is never needed.) With contact, the
// contact pass (src/solver/distributed_contact.hpp) follows the positions'
// halo, as it comes first in the serial step.
#include <chrono>
#include <cstdint>
#include <initializer_list>
#include <type_traits>
#include <vector>

#include "kernels/model_registry.hpp"
#include "kernels/paper_model.hpp"
#include "src/case/case_spec.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/timers.hpp"
#include "src/distributed/communicator.hpp"
#include "src/distributed/halo_exchange.hpp"
#include "src/distributed/local_state.hpp"
#include "src/distributed/part_message.hpp"
#include "src/solver/distributed_contact.hpp"
#include "src/solver/step.hpp"

namespace mpsolid {

// The corrected-gradient models: their strain pass is two gathers with a
// halo between (a bond's gap reads both ends' F), and their force pass
// reads the partners' (S + Q) A^-1.
template <class Model>
concept HasStressHalo = requires(Model m, ParticleStore& p, const BondTable& b, Range r) {
  m.compute_deformation_gradient(p, b, r);
  m.compute_hourglass_stress(p, b, r);
  m.deformation_gradient_field();
  m.stress_field();
};

template <class Model>
inline constexpr bool kDecomposable =
    std::is_same_v<Model, PaperModel> || std::is_same_v<Model, PaperConservativeModel> ||
    HasStressHalo<Model>;

// Adds the wall time of pass() to `seconds`, less the time it spent in
// halo exchanges (which `cost` counts).
template <class Pass>
void time_pass(double& seconds, const HaloCost& cost, Pass&& pass) {
  const double in_halos = cost.seconds;
  const auto start = std::chrono::steady_clock::now();
  pass();
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() -
             (cost.seconds - in_halos);
}

// The first halo of a step: positions (and, with rotation, the rotations
// and half angles).
template <bool Rotation>
void exchange_positions(const Communicator& world, LocalHalo& halo, ParticleStore& p,
                        HaloCost& cost) {
  if constexpr (Rotation)
    exchange_halo(world, halo,
                  {field_of(p.x), field_of(p.y), field_of(p.theta), field_of(p.half_cos),
                   field_of(p.half_sin)},
                  cost);
  else
    exchange_halo(world, halo, {field_of(p.x), field_of(p.y)}, cost);
}

// The strain pass of the owned particles, with the halos that leave every
// ghost's force-pass inputs at their owners' values.
template <class Model>
void decomposed_strain(Model& model, SolverState& s, const LocalLayout& layout, LocalHalo& halo,
                       const Communicator& world, HaloCost& cost) {
  ParticleStore& p = s.particles;
  if constexpr (HasStressHalo<Model>) {
    model.compute_deformation_gradient(p, s.bonds, layout.owned);
    exchange_halo(world, halo, {model.deformation_gradient_field()}, cost);
    model.compute_hourglass_stress(p, s.bonds, layout.owned);
    exchange_halo(world, halo, {model.stress_field()}, cost);
  } else {
    model.compute_strain(p, s.bonds, layout.owned);
    exchange_halo(world, halo, {field_of(p.strain), field_of(p.pressure)}, cost);
  }
}

// Advances this rank's local state by `steps` steps of dt (its team is the
// calling thread's: one OpenMP thread per rank for now). With contact, the
// list must have been built on every rank at the current positions.
template <class Model>
void advance_decomposed(Model& model, SolverState& s, const LocalLayout& layout, LocalHalo& halo,
                        RankContact& contact, const Communicator& world, double dt,
                        std::int64_t steps, HaloCost& cost, RankTimes& times) {
  static_assert(kDecomposable<Model>, "a model the decomposed step does not cover");
  constexpr bool rot = Model::uses_rotation;
  ParticleStore& p = s.particles;
  const Range moving_owned{std::max(layout.owned.begin, p.moving().begin),
                           std::min(layout.owned.end, p.moving().end)};
  if constexpr (rot) compute_half_angles(p, moving_owned);
  BodyKicks kicks(s.rigid_bodies.size());
  for (std::int64_t k = 0; k < steps; ++k, ++s.step) {
    exchange_positions<rot>(world, halo, p, cost);
    if (s.contact.enabled())
      time_pass(times.contact_seconds, cost,
                [&] { rank_contact_pass(contact, s, layout, world, s.step, cost); });
    if (!s.loads.empty()) activate_loads(p, s.loads, s.step);
    time_pass(times.strain_seconds, cost,
              [&] { decomposed_strain(model, s, layout, halo, world, cost); });
    // The force pass reads no position: a block's forces and its
    // integration follow each other, as in the team step.
    if (moving_owned.begin < moving_owned.end)
      time_pass(times.forces_seconds, cost, [&] {
        model.compute_forces_block(p, s.bonds, moving_owned);
        integrate_block<rot>(s, dt, moving_owned, kicks);
      });
  }
}

// One rank's part of a case: its particles and ghosts, its halo, its local
// state and the model made from it.
struct RankPart {
  LocalLayout layout;
  LocalHalo halo;
  SolverState local;
  RankContact contact;
  AnyModel model;
  HaloCost halo_cost;  // summed over every step so far
  RankTimes times;     // the passes' wall time, summed likewise
};

// The strain pass of the part's own particles at their current positions
// (half angles, the halos, the strain pass), as the serial refresh_fields
// gives them, then what rank 0's checks and outputs need of them, appended
// to `out`: the owned particles' strain and pressure, their strain energy
// summed in the ordered sums' whole chunks, and the model's integrity check
// among them (value, particle and neighbour in global storage indices,
// failed, the criterion's characters).
void append_rank_fields(RankPart& part, const Communicator& world, const IntegrityLimits& limits,
                        std::vector<double>& out);

// What rank 0 reads of every rank's fields.
struct RankFields {
  double strain_energy = 0;   // the chunk sums added in chunk order: the serial bits
  IntegrityReport integrity;  // the worst over the ranks (the first on ties)
};
// Reads one rank's fields (as append_rank_fields wrote them from `owned`,
// the rank's global storage range) into the whole state's strain and
// pressure, its chunk sums onto `chunk_sums`, and its integrity report
// into `fields` when worse.
void read_rank_fields(const std::vector<double>& in, std::size_t& at, Range owned,
                      ParticleStore& global, std::vector<double>& chunk_sums, RankFields& fields);

// The cut of the set-up state `global` over `ranks`, rigid and loaded
// bodies kept whole.
Decomposition decompose_state(const SolverState& global, int ranks);

// A rank's part ready to step: its local part (as rank 0 sends it) with the
// model made from it.
RankPart make_rank_part(const CaseSpec& spec, LocalPart local);
// This rank's part of the set-up state `global`, cut by decompose_state
// (every rank holding `global`, as the tests do). Throws
// std::invalid_argument for a case the decomposed step does not cover.
RankPart make_rank_part(const CaseSpec& spec, const SolverState& global, const Communicator& world);

// Advances the part by `steps` decomposed steps of dt. Its owned particles,
// bodies and loads must be current; the ghosts get their values from the
// halos before any pass reads them (with contact, the list is built first,
// from every rank's own candidates).
void advance_rank_part(RankPart& part, const Communicator& world, double dt, std::int64_t steps);

}  // namespace mpsolid
