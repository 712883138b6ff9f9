#include "src/solver/setup.hpp"

#include "src/solver/gas_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "neighbor/bond_search.hpp"
#include "src/core/region.hpp"
#include "src/core/region3.hpp"
#include "src/core/surface.hpp"
#include "src/core/surface3.hpp"

namespace mpsolid {

namespace {
struct NewParticle {
  double x, y, z;
  std::int32_t id, body;
};

// Storage rank of a body: walls first, then elastic bodies, then rigid
// bodies, each group in case order.
int group_of(Kind kind) {
  return kind == Kind::wall ? 0 : kind == Kind::elastic ? 1 : 2;
}
}  // namespace

SolverState set_up(const CaseSpec& spec, PhaseTimers& timers) {
  auto timer = timers.time(Phase::setup);
  SolverState s;

  // Ids in case order (bodies by name, sites row by row, in space layer by
  // layer).
  const bool space = spec.dimension == 3;
  std::vector<std::vector<NewParticle>> by_body(spec.bodies.size());
  std::int32_t next_id = 0;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const auto body = static_cast<std::int32_t>(b);
    if (space)
      for (const Point3& site : fill_shape3(spec.bodies[b].shape3, spec.l0))
        by_body[b].push_back({site.x, site.y, site.z, next_id++, body});
    else
      for (const Point2& site : fill_shape(spec.bodies[b].shape, spec.l0))
        by_body[b].push_back({site.x, site.y, 0.0, next_id++, body});
  }

  std::vector<std::size_t> order(spec.bodies.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return group_of(spec.bodies[a].kind) < group_of(spec.bodies[b].kind);
  });

  ParticleStore& p = s.particles;
  p.dimension = spec.dimension;
  p.resize(static_cast<std::size_t>(next_id));
  s.body_ranges.resize(spec.bodies.size());
  std::size_t next = 0;
  for (std::size_t b : order) {
    const BodySpec& body = spec.bodies[b];
    const Material& mat = spec.materials[static_cast<std::size_t>(body.material)];
    const double mass = space ? mat.density * spec.l0 * spec.l0 * spec.l0
                              : mat.density * spec.l0 * spec.l0 * spec.depth;
    // A square particle's, and a cube's about any axis through its centre.
    const double inertia = mass * spec.l0 * spec.l0 / 6.0;
    s.body_ranges[b] = {next, next + by_body[b].size()};
    for (const NewParticle& np : by_body[b]) {
      p.x[next] = p.x0[next] = np.x;
      p.y[next] = p.y0[next] = np.y;
      if (space) p.z[next] = p.z0[next] = np.z;
      p.id[next] = np.id;
      p.body[next] = np.body;
      p.material[next] = body.material;
      p.kind[next] = body.kind;
      p.inv_mass[next] = 1.0 / mass;
      p.inv_inertia[next] = 1.0 / inertia;
      p.lambda[next] = mat.lambda();
      p.mu[next] = mat.mu();
      ++next;
    }
  }
  p.set_kind_ranges();

  {
    auto t = timers.time(Phase::neighbors);
    s.bonds =
        build_bonds(p, space ? bond_geometry_3d(spec.l0) : bond_geometry(spec.l0, spec.depth));
  }

  for (std::size_t b : order)
    if (spec.bodies[b].kind == Kind::rigid) {
      s.rigid_bodies.push_back(make_rigid_body(p, spec.bodies[b].name, s.body_ranges[b]));
      s.rigid_bodies.back().motion = spec.bodies[b].motion;
    }

  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].hold != Hold::none)
      s.holds.push_back({s.body_ranges[b], spec.bodies[b].hold == Hold::x,
                         spec.bodies[b].hold == Hold::y, spec.bodies[b].hold == Hold::z});

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
    StepLoad load;
    load.name = l.name;
    load.range = s.body_ranges[static_cast<std::size_t>(l.body)];
    load.history = l.history;
    load.start = l.start;
    if (l.type == LoadSpec::Type::step) {
      load.fx = l.force[0];
      load.fy = l.force[1];
      load.fz = l.force[2];
    } else if (l.type == LoadSpec::Type::pressure && spec.dimension == 3) {
      const Shape3& shape = spec.bodies[static_cast<std::size_t>(l.body)].shape3;
      const Surface3 surface = build_surface3(shape, fill_shape3(shape, spec.l0), spec.l0);
      load.surface = make_pressure_surface3(surface, select_quads(surface, l.surface),
                                            load.range.begin, l.pressure);
    } else if (l.type == LoadSpec::Type::pressure) {
      const Shape& shape = spec.bodies[static_cast<std::size_t>(l.body)].shape;
      const Surface surface = build_surface(shape, fill_shape(shape, spec.l0), spec.l0);
      load.surface = make_pressure_surface(surface, select_segments(surface, l.surface),
                                           load.range.begin, l.pressure, spec.depth);
    } else {
      // m a on each particle: the body's mass times a, shared equally.
      const double mass = static_cast<double>(load.range.size()) / p.inv_mass[load.range.begin];
      load.fx = mass * l.acceleration[0];
      load.fy = mass * l.acceleration[1];
      load.fz = mass * l.acceleration[2];
    }
    s.loads.push_back(load);
  }
  add_gas_loads(spec, s);
  return s;
}

void schedule_loads(SolverState& s, const CaseSpec& spec) {
  // The first step k with k dt >= t.
  const auto first_step_at = [&](double t) {
    return static_cast<std::int64_t>(std::ceil(t / spec.dt - 1e-9));
  };
  for (std::size_t k = 0; k < spec.loads.size(); ++k)
    s.loads[k].first_step = first_step_at(spec.loads[k].start);
  if (spec.damping.coefficient > 0)
    s.damping = {spec.damping.coefficient, first_step_at(spec.damping.start),
                 first_step_at(spec.damping.end)};
}

}  // namespace mpsolid
