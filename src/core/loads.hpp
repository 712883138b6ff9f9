#pragma once
// External forces on bodies, each following its time history
// (src/core/load_history.hpp), and the work they do: a force shared equally
// by a body's particles, or a pressure on part of its surface
// (src/core/surface.hpp) along the current outward normals (a follower load).
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/particle_store.hpp"
#include "src/core/surface.hpp"
#include "src/core/surface3.hpp"

namespace mpsolid {

// A pressure's part of a body's surface: its selected segments (in space,
// quadrilaterals), the nodes at their ends (weights over storage indices),
// and the running step's node positions and forces.
//
// A body may be split between ranks (or threads stepping their own parts):
// every part holds every node and segment, but positions only the nodes
// whose host (a node's first weight) it owns, from the host's lattice
// neighbours (its ghosts at most); the parts then share those positions, so
// each computes every node's force, and the work, with the serial bits, and
// adds to its own particles their part.
struct PressureSurface {
  static constexpr std::uint32_t kElsewhere = std::numeric_limits<std::uint32_t>::max();
  double pressure = 0;  // Pa at a factor of 1
  double depth = 0;     // m (the plane's; 1 in space)
  // Node k's weights over [offsets[k], offsets[k + 1]); a particle this
  // part does not hold is kElsewhere (never read: its node is not `hosted`).
  std::vector<std::uint32_t> offsets{0}, particle;
  std::vector<double> weight;
  std::vector<std::uint32_t> hosted;    // the nodes this part positions, increasing
  std::vector<std::uint32_t> from, to;  // each segment's nodes
  std::vector<std::uint32_t> quad;      // in space: four nodes per quadrilateral
  // The running step: each node's position at its start, and its force
  // (z and fz in space only).
  std::vector<double> x, y, fx, fy, z, fz;
  // Node forces set from outside (N: the gas's, held over its step), used
  // instead of the pressure when not empty.
  std::vector<double> given_fx, given_fy;
  // This part's particles that the nodes' forces reach (increasing), each
  // weight's place among them (kElsewhere for another part's particle), and
  // their forces in the running step.
  std::vector<std::uint32_t> targets, slot;
  std::vector<double> target_fx, target_fy, target_fz;
  std::size_t nodes() const { return offsets.size() - 1; }
  bool in_space() const { return !quad.empty(); }
  // What a checkpoint or a rank's slice keeps of the running step, in order.
  std::vector<std::vector<double>*> running_fields() { return {&x, &y, &given_fx, &given_fy, &z}; }
  std::vector<const std::vector<double>*> running_fields() const {
    return {&x, &y, &given_fx, &given_fy, &z};
  }
  std::size_t running_size() const {
    std::size_t n = 0;
    for (const std::vector<double>* v : running_fields()) n += v->size();
    return n;
  }
  // Sizes the running step's node and target forces (fz, target_fz in
  // space only), or its target forces alone (a part's copy keeps the
  // whole's node forces).
  void size_forces() {
    fx.assign(nodes(), 0.0);
    fy.assign(nodes(), 0.0);
    fz.assign(in_space() ? nodes() : 0, 0.0);
    size_target_forces();
  }
  void size_target_forces() {
    target_fx.assign(targets.size(), 0.0);
    target_fy.assign(targets.size(), 0.0);
    target_fz.assign(in_space() ? targets.size() : 0, 0.0);
  }
};

// The segments `segments` of `surface`, whose sites are storage indices
// `first` + site, under `pressure` over `depth`.
PressureSurface make_pressure_surface(const Surface& surface,
                                      const std::vector<std::uint32_t>& segments, std::size_t first,
                                      double pressure, double depth);
// In space: the quadrilaterals `quads` of `surface`.
PressureSurface make_pressure_surface3(const Surface3& surface,
                                       const std::vector<std::uint32_t>& quads, std::size_t first,
                                       double pressure);
// The surface as a part sees it: `local_of(i)` is the part's index of
// storage index i, or kElsewhere where it does not hold i; `owned(local)`
// whether the part steps that particle.
PressureSurface local_pressure_surface(const PressureSurface& whole,
                                       const std::function<std::uint32_t(std::uint32_t)>& local_of,
                                       const std::function<bool(std::uint32_t)>& owned);

struct StepLoad {
  std::string name;
  Range range;                  // the loaded body's particles
  double fx = 0, fy = 0;        // total force (N) at a factor of 1
  double fz = 0;                // in space
  LoadHistory history;          // the factor over time since `start`
  double start = 0;             // s: when it switches on
  std::int64_t first_step = 0;  // first step k with k dt >= start
  // Centroid of the body at first_step, once reached. For a constant force,
  // the work telescopes: W = F . (c(now) - c(first_step)), exactly, because
  // each step moves every particle by dt v and W_step = sum (F/N) . dt v.
  bool active = false;
  double cx_on = 0, cy_on = 0, cz_on = 0;  // cz in space
  // A varying force: the factor of the step that ran last (or runs now),
  // the centroid at that step's start, and the work of the steps before it.
  double factor = 1;
  double cx_last = 0, cy_last = 0, cz_last = 0;
  double work = 0;
  // A pressure load's surface; empty for a force. A body's gas load is a
  // pressure load over its whole surface with given node forces.
  PressureSurface surface;
  bool is_pressure() const { return !surface.from.empty() || surface.in_space(); }
};

// A pressure load's node forces and their particles' sums, from its nodes'
// positions (surface.x, y) and its factor: called each step, and where a
// load's running step is restored (a checkpoint, a rank's slice).
void pressure_forces(StepLoad& load);

// A pressure load whose node forces are about to be changed between steps
// (a gas load's, by the gas): adds the running step's work so far to its
// work and restarts the running step at every node's current position
// `xyz` (x, y, z per node, z = 0 in the plane), so the work is the same
// whichever way the new forces reach the particles.
void close_running_step_at(StepLoad& load, const std::vector<double>& xyz);

// The current positions of the nodes this part hosts of each active
// pressure load of `loads`, appended as (the load's place among the
// pressure loads, node, x, y, z) each: what a part sends for a pressure's
// work when no process holds the whole state.
void append_hosted_node_positions(const ParticleStore& p, const std::vector<StepLoad>& loads,
                                  std::vector<double>& out);
// A pressure load's work so far (load_work's) from every node's current
// position, `xyz` (x, y, z per node, z = 0 in the plane).
double pressure_work_at(const StepLoad& load, const std::vector<double>& xyz);

// Whether any of `loads` is a pressure.
bool any_pressure(const std::vector<StepLoad>& loads);

// Every part's values, concatenated in part order, on every part (a
// collective call): how the parts of a split body share its nodes.
using GatherParts = std::function<std::vector<double>(const std::vector<double>&)>;

// At the start of `step` (with its start-of-step positions, ghosts
// included): switches on the loads that start at it, recording the body's
// centroid, and for the varying ones adds the previous step's work and
// takes this step's factor. With `gather` (a part of several), the
// pressure loads' hosted nodes are shared first: every part calls it once
// in a step where a pressure load is on.
void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                    double dt, const GatherParts* gather = nullptr);

// Adds each active load's share to the forces of the particles in `block`
// (after the force pass), loads in order. Serial: the step calls it per block.
void apply_loads(ParticleStore& p, const std::vector<StepLoad>& loads, Range block);

// Work done by one load, and by all, up to the current state.
double load_work(const ParticleStore& p, const StepLoad& load);
double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads);

// Centroid of a range of particles (ordered sum).
void centroid(const ParticleStore& p, Range range, double& cx, double& cy);
// The same with z (0 in the plane).
void centroid(const ParticleStore& p, Range range, double& cx, double& cy, double& cz);

}  // namespace mpsolid
