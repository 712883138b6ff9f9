#include "src/solver/setup.hpp"

#include "src/solver/gas_outlines.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "kernels/model_registry.hpp"
#include "neighbor/bond_search.hpp"
#include "src/core/region.hpp"
#include "src/core/region3.hpp"
#include "src/core/stability.hpp"
#include "src/core/surface.hpp"
#include "src/core/surface3.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/initial_motion.hpp"

namespace mpsolid {

namespace {
// Storage rank of a body: walls first, then elastic bodies, then rigid
// bodies, each group in case order.
int group_of(Kind kind) {
  return kind == Kind::wall ? 0 : kind == Kind::elastic ? 1 : 2;
}
}  // namespace

void visit_body_sites(const CaseSpec& spec, std::size_t b,
                      const std::function<void(std::size_t, const Point3&)>& site) {
  std::size_t k = 0;
  if (spec.dimension == 3)
    visit_shape3_sites(spec.bodies[b].shape3, spec.l0, [&](Point3 q) { site(k++, q); });
  else
    visit_shape_sites(spec.bodies[b].shape, spec.l0, [&](Point2 q) {
      site(k++, Point3{q.x, q.y, 0.0});
    });
}

BodyLayout body_layout(const CaseSpec& spec) {
  BodyLayout out;
  const std::size_t bodies = spec.bodies.size();
  out.range.resize(bodies);
  out.first_id.resize(bodies);
  std::vector<std::size_t> count(bodies);
  std::size_t ids = 0;
  for (std::size_t b = 0; b < bodies; ++b) {
    count[b] = static_cast<std::size_t>(spec.bodies[b].site_count(spec.l0, spec.dimension));
    out.first_id[b] = ids;
    ids += count[b];
  }
  out.order.resize(bodies);
  std::iota(out.order.begin(), out.order.end(), 0);
  std::stable_sort(out.order.begin(), out.order.end(), [&](std::size_t a, std::size_t c) {
    return group_of(spec.bodies[a].kind) < group_of(spec.bodies[c].kind);
  });
  std::size_t next = 0;
  for (const std::size_t b : out.order) {
    out.range[b] = {next, next + count[b]};
    next += count[b];
  }
  out.total = next;
  return out;
}

void place_particle(ParticleStore& p, std::size_t i, const CaseSpec& spec, std::size_t b,
                    const Point3& site, std::size_t id) {
  const BodySpec& body = spec.bodies[b];
  const Material& mat = spec.materials[static_cast<std::size_t>(body.material)];
  const bool space = spec.dimension == 3;
  const double mass = space ? mat.density * spec.l0 * spec.l0 * spec.l0
                            : mat.density * spec.l0 * spec.l0 * spec.depth;
  // A square particle's, and a cube's about any axis through its centre.
  const double inertia = mass * spec.l0 * spec.l0 / 6.0;
  p.x[i] = p.x0[i] = site.x;
  p.y[i] = p.y0[i] = site.y;
  if (space) p.z[i] = p.z0[i] = site.z;
  p.id[i] = static_cast<std::int32_t>(id);
  p.body[i] = static_cast<std::int32_t>(b);
  p.material[i] = body.material;
  p.kind[i] = body.kind;
  p.inv_mass[i] = 1.0 / mass;
  p.inv_inertia[i] = 1.0 / inertia;
  p.lambda[i] = mat.lambda();
  p.mu[i] = mat.mu();
}

StepLoad body_load(const LoadSpec& l, Range range, const ParticleStore& p) {
  StepLoad load;
  load.name = l.name;
  load.range = range;
  load.history = l.history;
  load.start = l.start;
  if (l.type == LoadSpec::Type::step) {
    load.fx = l.force[0];
    load.fy = l.force[1];
    load.fz = l.force[2];
  } else if (l.type != LoadSpec::Type::pressure) {
    // m a on each particle: the body's mass times a, shared equally.
    const double mass = static_cast<double>(range.size()) / p.inv_mass[range.begin];
    load.fx = mass * l.acceleration[0];
    load.fy = mass * l.acceleration[1];
    load.fz = mass * l.acceleration[2];
  }
  return load;
}

PressureSurface case_pressure_surface(const CaseSpec& spec, const LoadSpec& l, std::size_t first) {
  const BodySpec& body = spec.bodies[static_cast<std::size_t>(l.body)];
  if (spec.dimension == 3) {
    const Surface3 surface =
        build_surface3(body.shape3, fill_shape3(body.shape3, spec.l0), spec.l0);
    return make_pressure_surface3(surface, select_quads(surface, l.surface), first, l.pressure);
  }
  const Surface surface = build_surface(body.shape, fill_shape(body.shape, spec.l0), spec.l0);
  return make_pressure_surface(surface, select_segments(surface, l.surface), first, l.pressure,
                               spec.depth);
}

HeldRange body_hold(const BodySpec& body, Range range) {
  return {range, body.hold == Hold::x, body.hold == Hold::y, body.hold == Hold::z};
}

BondGeometry case_bond_geometry(const CaseSpec& spec) {
  return spec.dimension == 3 ? bond_geometry_3d(spec.l0) : bond_geometry(spec.l0, spec.depth);
}

SolverState set_up(const CaseSpec& spec, PhaseTimers& timers) {
  auto timer = timers.time(Phase::setup);
  SolverState s;

  // Ids in case order (bodies by name, sites row by row, in space layer by
  // layer); storage grouped by kind.
  const bool space = spec.dimension == 3;
  const BodyLayout layout = body_layout(spec);
  const std::vector<std::size_t>& order = layout.order;
  ParticleStore& p = s.particles;
  p.dimension = spec.dimension;
  p.resize(layout.total);
  s.body_ranges = layout.range;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& site) {
      place_particle(p, layout.range[b].begin + k, spec, b, site, layout.first_id[b] + k);
    });
  p.set_kind_ranges();

  {
    auto t = timers.time(Phase::neighbors);
    s.bonds = build_bonds(p, case_bond_geometry(spec));
  }

  for (std::size_t b : order)
    if (spec.bodies[b].kind == Kind::rigid) {
      s.rigid_bodies.push_back(make_rigid_body(p, spec.bodies[b].name, s.body_ranges[b]));
      s.rigid_bodies.back().motion = spec.bodies[b].motion;
    }

  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].hold != Hold::none)
      s.holds.push_back(body_hold(spec.bodies[b], s.body_ranges[b]));

  // Probes: the nearest particle to the point, lowest id on a tie.
  for (const ProbeSpec& probe : spec.probes) {
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double dx = p.x0[i] - probe.at[0], dy = p.y0[i] - probe.at[1];
      const double dz = space ? p.z0[i] - probe.at[2] : 0.0;
      const double d2 = dx * dx + dy * dy + dz * dz;
      if (d2 < best_d2 || (d2 == best_d2 && p.id[i] < p.id[best])) {
        best = i;
        best_d2 = d2;
      }
    }
    s.probes.push_back(best);
  }

  for (const LoadSpec& l : spec.loads) {
    StepLoad load = body_load(l, s.body_ranges[static_cast<std::size_t>(l.body)], p);
    if (l.type == LoadSpec::Type::pressure)
      load.surface = case_pressure_surface(spec, l, load.range.begin);
    s.loads.push_back(load);
  }
  // The gas's loads after the case's own.
  for (StepLoad& load : gas_loads(spec, s.body_ranges)) s.loads.push_back(std::move(load));
  return s;
}

double case_energy_floor(const CaseSpec& spec, const std::vector<Range>& body_ranges) {
  std::vector<ParticleGroup> groups;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    groups.push_back(
        {body_ranges[b].size(), spec.materials[static_cast<std::size_t>(spec.bodies[b].material)]});
  return energy_balance_floor(groups, spec.particle_volume());
}

void finish_set_up(SolverState& s, const CaseSpec& spec) {
  s.contact = make_contact(spec, s);
  apply_initial_motion(s, spec, model_info(spec.model).uses_rotation);
}

void put_loads_in_case_order(const CaseSpec& spec, std::vector<StepLoad>& loads) {
  std::vector<StepLoad> ordered;
  const auto take = [&](const std::string& name) {
    for (StepLoad& load : loads)
      if (load.name == name) ordered.push_back(std::move(load));
  };
  for (const LoadSpec& l : spec.loads) take(l.name);
  // The gas's loads after the case's own, as set_up makes them.
  for (const int b : spec.gas.bodies)
    take(kGasLoadPrefix + spec.bodies[static_cast<std::size_t>(b)].name);
  loads = std::move(ordered);
}

void schedule_loads(SolverState& s, const CaseSpec& spec) {
  // The first step k with k dt >= t.
  const auto first_step_at = [&](double t) {
    return static_cast<std::int64_t>(std::ceil(t / spec.dt - 1e-9));
  };
  for (StepLoad& load : s.loads) load.first_step = first_step_at(load.start);
  if (spec.damping.coefficient > 0)
    s.damping = {spec.damping.coefficient, first_step_at(spec.damping.start),
                 first_step_at(spec.damping.end)};
}

}  // namespace mpsolid
