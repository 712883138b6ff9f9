#pragma once
// From a validated case to the initial solver state: lattice particles,
// storage grouped by kind, masses, the bond table, rigid bodies and loads.
#include <functional>
#include <vector>

#include "src/case/case_spec.hpp"
#include "src/core/solver_state.hpp"
#include "src/core/timers.hpp"

namespace mpsolid {

// Particles, bonds, rigid bodies, holds, probes and loads; the loads' first
// steps are set by schedule_loads once the case's dt is fixed.
SolverState set_up(const CaseSpec& spec, PhaseTimers& timers);

// Where each body's particles go, from its sites' count alone: its storage
// range (walls, then elastic, then rigid bodies, each group in case order)
// and its first id (ids in case order, each body's in its fill order).
struct BodyLayout {
  std::vector<Range> range;
  std::vector<std::size_t> first_id;
  std::vector<std::size_t> order;  // the bodies in storage order
  std::size_t total = 0;
};
BodyLayout body_layout(const CaseSpec& spec);
// Calls site(k, position) for each lattice site of body b in its fill order
// (k from 0; z = 0 in the plane).
void visit_body_sites(const CaseSpec& spec, std::size_t b,
                      const std::function<void(std::size_t, const Point3&)>& site);
// A load's switch-on, history and force (a step's, or its acceleration times
// the body's mass) on the particles `range` of `p`; a pressure's surface is
// set up apart.
StepLoad body_load(const LoadSpec& l, Range range, const ParticleStore& p);
// A pressure load's surface (its selected segments, or in space quads) over
// its whole body, whose first particle is storage index `first`.
PressureSurface case_pressure_surface(const CaseSpec& spec, const LoadSpec& l, std::size_t first);
// A held body's hold over the particles `range`.
HeldRange body_hold(const BodySpec& body, Range range);
// The bond geometry of the case's lattice (in the plane, over its depth).
BondGeometry case_bond_geometry(const CaseSpec& spec);
// Particle i of `p` as set-up makes it: a site of body b with its id.
void place_particle(ParticleStore& p, std::size_t i, const CaseSpec& spec, std::size_t b,
                    const Point3& site, std::size_t id);

// The energy balance's floor (energy_balance_floor) of the case's bodies,
// their storage ranges `body_ranges`.
double case_energy_floor(const CaseSpec& spec, const std::vector<Range>& body_ranges);

// `loads` (some of the case's and of its gas's, in any order) in the order
// set_up makes them: the case's, then the gas's.
void put_loads_in_case_order(const CaseSpec& spec, std::vector<StepLoad>& loads);

// Each load's first step k (k dt >= its start) and the damping's window;
// spec.dt must be fixed. A rank's part schedules its own loads likewise.
void schedule_loads(SolverState& s, const CaseSpec& spec);

// A set-up state made ready to run but for its schedule (no dt read):
// contact's candidates, the initial motion.
void finish_set_up(SolverState& s, const CaseSpec& spec);

}  // namespace mpsolid
