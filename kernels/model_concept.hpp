#pragma once
// What a bond model is (MODEL.md sections 2, 4b, 5, 7): a type the time step,
// the diagnostics and the stable-step estimate are written once against.
//
// A model makes its own per-bond coefficients from the bond table's topology
// and reference geometry at construction, reads its options from its own
// case section (options_section, validated against options() by the case
// reader), and then runs two gather passes per step:
//   strain_pass: position-dependent fields of every particle in `range`
//     (strain, pressure and whatever the force pass needs), with the halos
//     over MPI ranks of what it and the force pass read of a partner
//     (share_motion before it); compute_strain is the same with no halo;
//   compute_forces (compute_forces_block per block): force and torque of
//     the moving particles in `range`.
// Each index writes only its own outputs, so any thread schedule gives the
// same bits. A new model is one file in kernels/ and one line in
// kernels/model_registry.hpp.
#include <concepts>
#include <cstddef>

#include "kernels/model_common.hpp"
#include "src/core/bonds.hpp"
#include "src/core/option_table.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/core/particle_field.hpp"
#include "src/core/particle_store.hpp"

namespace mpsolid {

template <class M>
concept BondModel = requires(M m, const M cm, ParticleStore& p, const ParticleStore& cp,
                             const BondTable& bonds, const OptionValues& options, Range range,
                             std::size_t i, const IntegrityLimits& limits, NoHalo& halo) {
  { M::name } -> std::convertible_to<const char*>;
  { M::uses_rotation } -> std::convertible_to<bool>;       // spins and half angles are integrated
  { M::rotation_invariant } -> std::convertible_to<bool>;  // a rigid rotation is stress-free
  // false: compute_forces_block(p, bonds, block) serially gives a block's forces
  // from the strain pass's fields alone, so the step integrates the block
  // right after it with no barrier.
  { M::forces_read_positions } -> std::convertible_to<bool>;
  { M::options_section } -> std::convertible_to<const char*>;  // "" if it takes no options
  { M::options() } -> std::same_as<std::vector<OptionSpec>>;   // that section's table
  M(cp, bonds, options);
  m.compute_strain(p, bonds, range);
  // The strain pass as the step runs it, with its halos (src/solver/step.hpp):
  // what it reads of a partner's motion (share_motion posts it, the strain
  // pass finishes it before it reads a ghost), and after each stage the
  // fields the next stage or the force pass read of a partner. It leaves
  // the last (what the force pass reads) posted: the step finishes it once
  // the forces that read no ghost are done.
  M::share_motion(p, halo);
  m.strain_pass(p, bonds, range, halo);
  cm.compute_forces(p, bonds, range);
  // The particle's share of the strain energy (needs a current strain pass).
  { cm.particle_strain_energy(cp, bonds, i) } -> std::same_as<double>;
  // The model's measure of a broken state (an inverted bond, a collapsed J),
  // the worst among the particles of `range`.
  { cm.check_integrity(cp, bonds, limits, range) } -> std::same_as<IntegrityReport>;
}
&&(M::forces_read_positions || requires(const M cm, ParticleStore& p, const BondTable& bonds,
                                        Range range) { cm.compute_forces_block(p, bonds, range); });

// The model's strain energy of the particles of `range` (a current strain
// pass), summed as ordered_sum sums (over ranks, each rank's share of the
// same chunks: src/distributed/ordered_sum_parts.hpp).
template <class M>
double summed_strain_energy(const M& model, const ParticleStore& p, const BondTable& bonds,
                            Range range) {
  return ordered_sum<1>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 1>{model.particle_strain_energy(p, bonds, i)};
  })[0];
}

}  // namespace mpsolid
