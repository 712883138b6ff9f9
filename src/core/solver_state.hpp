#pragma once
// Everything a run's physics reads and writes: the particles, the fixed bond
// table, rigid bodies, loads and holds, where each body and probe lies in
// storage, and the step reached. The time step is not here: it belongs to the
// case (CaseSpec::dt), which is fixed before the state is built.
#include <cstdint>
#include <vector>

#include "src/core/bonds.hpp"
#include "src/core/contact_state.hpp"
#include "src/core/damping.hpp"
#include "src/core/holds.hpp"
#include "src/core/loads.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/rigid_body.hpp"

namespace mpsolid {

struct SolverState {
  ParticleStore particles;
  BondTable bonds;
  std::vector<RigidBody> rigid_bodies;
  std::vector<StepLoad> loads;
  std::vector<HeldRange> holds;
  ContactState contact;             // empty unless the case has contact
  Damping damping;                  // none unless the case has [damping]
  std::vector<Range> body_ranges;   // storage range of each body (case order)
  std::vector<std::size_t> probes;  // storage index of each probe's particle (case order)
  std::int64_t step = 0;
  // The largest external work seen by a stability check: the energy scale of
  // the balance check, which must not shrink when a load gets work back.
  double peak_work = 0;
};

}  // namespace mpsolid
