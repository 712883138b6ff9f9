#include "src/solver/gas_coupling.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/rigid_body.hpp"
#include "src/gas/shock_relations.hpp"

namespace mpsolid {

namespace {
GasPrimitive<2> primitive_of(const GasStateSpec& s) {
  return {s.density, {s.velocity[0], s.velocity[1]}, s.pressure};
}

// The gas behind the case's shock, moving with it.
GasPrimitive<2> shocked(const GasSpec& g) {
  const ShockedGas behind =
      shocked_gas({g.initial.density, 0.0, g.initial.pressure}, g.mach, g.gamma);
  return {behind.behind.rho, {g.direction * behind.behind.u, 0.0}, behind.behind.p};
}
}  // namespace

namespace {
GasSolver<2> make_gas(const GasSpec& g) {
  GasGrid<2> grid;
  grid.h = g.cell;
  grid.origin = {g.x[0], g.y[0]};
  grid.cells = {static_cast<int>(std::round((g.x[1] - g.x[0]) / g.cell)),
                static_cast<int>(std::round((g.y[1] - g.y[0]) / g.cell))};
  GasSolver<2>::Boundaries edges;
  for (int a = 0; a < 2; ++a)
    for (int side = 0; side < 2; ++side) {
      GasBoundary<2>& e = edges[a][side];
      switch (g.edges[a][side]) {
        case GasSpec::Edge::slip_wall:
          e.kind = GasBoundaryKind::slip_wall;
          break;
        case GasSpec::Edge::outflow:
          e.kind = GasBoundaryKind::outflow;
          break;
        case GasSpec::Edge::inflow:
          e.kind = GasBoundaryKind::inflow;
          e.state = g.inflow_given ? primitive_of(g.inflow) : shocked(g);
          break;
      }
    }
  GasSolver<2> gas(grid, g.gamma, edges);
  gas.set_solid_pressure(g.reference_pressure);
  const GasPrimitive<2> behind = g.mach > 0 ? shocked(g) : GasPrimitive<2>{};
  for (int j = 0; j < grid.cells[1]; ++j)
    for (int i = 0; i < grid.cells[0]; ++i) {
      const auto c = grid.centre({i, j});
      GasPrimitive<2> w = primitive_of(g.initial);
      for (const GasSpec::Region& r : g.regions)
        if (shape_contains(r.shape, {c[0], c[1]})) w = primitive_of(r.state);
      if (g.mach > 0 && g.direction * (c[0] - g.shock_x) < 0) w = behind;
      gas.set({i, j}, w);
    }
  return gas;
}
}  // namespace

GasCoupling::GasCoupling(const CaseSpec& spec, const SolverState& head)
    : spec_(spec.gas),
      depth_(spec.depth),
      gas_(make_gas(spec.gas)),
      outlines_(gas_outlines(spec, head.body_ranges)) {
  // Each outline's gas load (a moving body's) and driven rigid body.
  std::size_t pieces = 0;
  for (std::size_t k = 0; k < outlines_.size(); ++k) {
    const std::string& body = spec.bodies[static_cast<std::size_t>(spec_.bodies[k])].name;
    Outline o;
    const auto load = std::find_if(head.loads.begin(), head.loads.end(), [&](const StepLoad& l) {
      return l.name == kGasLoadPrefix + body;
    });
    if (load != head.loads.end()) o.load = static_cast<int>(load - head.loads.begin());
    const auto rigid = std::find_if(head.rigid_bodies.begin(), head.rigid_bodies.end(),
                                    [&](const RigidBody& r) { return r.name == body; });
    if (rigid != head.rigid_bodies.end() && rigid->motion.on)
      o.driven = static_cast<int>(rigid - head.rigid_bodies.begin());
    o.first_piece = pieces;
    pieces += outlines_[k].from.size();
    coupled_.push_back(o);
  }
}

void GasCoupling::place_walls(const OutlineMotion& now) {
  last_walls_ = walls(now);
  gas_.set_walls(last_walls_);
}

std::vector<GasWallSegment> GasCoupling::walls(const OutlineMotion& now) const {
  std::vector<GasWallSegment> out;
  for (std::size_t k = 0; k < outlines_.size(); ++k) {
    const PressureSurface& s = outlines_[k];
    const std::vector<double>& m = now.at(k);  // x, y, vx, vy per node
    for (std::size_t g = 0; g < s.from.size(); ++g) {
      const double *a = &m.at(4 * s.from[g]), *b = &m.at(4 * s.to[g]);
      out.push_back({{a[0], a[1]}, {b[0], b[1]}, {a[2], a[3]}, {b[2], b[3]}});
    }
  }
  return out;
}

double GasCoupling::steps_within_half_a_cell(const SolverState& head, double dt, double fastest,
                                             double limit) const {
  // A driven body's speed is known ahead: a step or a ramp in its motion
  // must not carry its wall further than the gas can follow in one window.
  std::vector<std::pair<const RigidBody*, double>> driven;  // body, reach from its centroid
  for (std::size_t k = 0; k < coupled_.size(); ++k) {
    const Outline& o = coupled_[k];
    if (o.driven < 0) continue;
    const RigidBody& r = head.rigid_bodies[static_cast<std::size_t>(o.driven)];
    double reach = 0;  // of its outline's nodes, for its spin
    for (std::size_t g = 0; g < outlines_[k].from.size(); ++g)
      for (const auto& node : {last_walls_[o.first_piece + g].a, last_walls_[o.first_piece + g].b})
        reach = std::max(reach, std::hypot(node[0] - r.xg, node[1] - r.yg));
    driven.emplace_back(&r, reach);
  }
  if (driven.empty()) return limit;
  double travel = 0;
  for (double k = 0; k < limit; ++k) {
    const double t = (static_cast<double>(head.step) + k) * dt;
    double speed = fastest;
    for (const auto& [r, reach] : driven)
      speed = std::max(speed, std::abs(r->motion.factor(t, dt)) *
                                  (std::hypot(r->motion.velocity[0], r->motion.velocity[1]) +
                                   std::abs(r->motion.spin[2]) * reach));
    travel += speed * dt;
    if (travel > 0.5 * spec_.cell) return std::max(k, 1.0);
  }
  return limit;
}

GasNodeForces GasCoupling::window(const SolverState& head, const OutlineMotion& now, double dt) {
  place_walls(now);
  const std::vector<GasWallSegment>& segments = last_walls_;
  // The window: as many solid steps as the gas's CFL step holds, and no
  // more than a wall crosses half a cell in; or one solid step in as many
  // gas steps as it needs.
  double fastest = 0;
  for (const GasWallSegment& s : segments)
    fastest = std::max({fastest, std::hypot(s.va[0], s.va[1]), std::hypot(s.vb[0], s.vb[1])});
  const double gas_dt = gas_.stable_dt(spec_.cfl);
  double fit = std::floor(gas_dt / dt);
  if (fastest > 0) fit = std::min(fit, std::floor(0.5 * spec_.cell / (fastest * dt)));
  if (fit > 1) fit = steps_within_half_a_cell(head, dt, fastest, fit);
  const std::int64_t window = fit >= 1 ? static_cast<std::int64_t>(std::min(fit, 1e9)) : 1;
  const int substeps = fit >= 1 ? 1 : static_cast<int>(std::ceil(dt / gas_dt));
  const double step = static_cast<double>(window) * dt / substeps;
  std::vector<std::array<double, 4>> forces(segments.size());
  for (int k = 0; k < substeps; ++k) {
    gas_.advance(step);
    for (std::size_t g = 0; g < forces.size(); ++g)
      for (int c = 0; c < 4; ++c) forces[g][c] += gas_.wall_forces()[g][c] / substeps;
  }
  gas_steps_ += substeps;
  gas_time_ += static_cast<double>(window) * dt;
  // Each moving body's node forces, N over the depth: its x components,
  // then its y components.
  GasNodeForces out;
  for (std::size_t k = 0; k < coupled_.size(); ++k) {
    if (coupled_[k].load < 0) continue;
    const PressureSurface& s = outlines_[k];
    const std::size_t first = out.size(), n = s.nodes();
    out.resize(first + 2 * n, 0.0);
    double* fx = out.data() + first;
    double* fy = fx + n;
    for (std::size_t g = 0; g < s.from.size(); ++g) {
      const std::array<double, 4>& f = forces[coupled_[k].first_piece + g];
      fx[s.from[g]] += depth_ * f[0];
      fy[s.from[g]] += depth_ * f[1];
      fx[s.to[g]] += depth_ * f[2];
      fy[s.to[g]] += depth_ * f[3];
    }
  }
  next_ = head.step + window;
  return out;
}

GasCoupling::Saved GasCoupling::saved() const {
  Saved out;
  const char* names[] = {"rho", "rho_u", "rho_v", "E"};
  for (int v = 0; v < GasSolver<2>::kVars; ++v) out.emplace_back(names[v], gas_.conserved(v));
  std::vector<double> walls;
  for (const GasWallSegment& w : last_walls_)
    walls.insert(walls.end(), {w.a[0], w.a[1], w.b[0], w.b[1], w.va[0], w.va[1], w.vb[0], w.vb[1]});
  out.emplace_back("walls", walls);
  const GasExchange<2>& x = gas_.exchange();
  out.emplace_back("exchange",
                   std::vector<double>{x.inflow.mass, x.inflow.momentum[0], x.inflow.momentum[1],
                                       x.inflow.energy, x.wall_impulse[0], x.wall_impulse[1],
                                       x.wall_work, x.solid_work, x.lost.mass, x.lost.momentum[0],
                                       x.lost.momentum[1], x.lost.energy});
  out.emplace_back("clock", std::vector<double>{static_cast<double>(next_),
                                                static_cast<double>(gas_steps_), gas_time_});
  return out;
}

void GasCoupling::restore(const Saved& saved) {
  const auto find = [&](const std::string& name, std::size_t size) -> const std::vector<double>& {
    for (const auto& [n, values] : saved)
      if (n == name) {
        if (size > 0 && values.size() != size)
          throw InputError(fmt::format("the checkpoint's gas.{} has {} values, this gas needs {}",
                                       name, values.size(), size));
        return values;
      }
    throw InputError(
        fmt::format("the checkpoint has no gas.{}: it was written for a case "
                    "without this gas",
                    name));
  };
  const std::vector<double>& w = find("walls", 8 * last_walls_.size());
  std::vector<GasWallSegment> walls(last_walls_.size());
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const double* v = w.data() + 8 * k;
    walls[k] = {{v[0], v[1]}, {v[2], v[3]}, {v[4], v[5]}, {v[6], v[7]}};
  }
  gas_ = make_gas(spec_);
  last_walls_ = walls;
  gas_.set_walls(last_walls_);
  const char* names[] = {"rho", "rho_u", "rho_v", "E"};
  for (int v = 0; v < GasSolver<2>::kVars; ++v)
    gas_.set_conserved(v, find(names[v], gas_.grid().storage()));
  const std::vector<double>& e = find("exchange", 12);
  GasExchange<2> x;
  x.inflow = {e[0], {e[1], e[2]}, e[3]};
  x.wall_impulse = {e[4], e[5]};
  x.wall_work = e[6];
  x.solid_work = e[7];
  x.lost = {e[8], {e[9], e[10]}, e[11]};
  gas_.set_exchange(x);
  const std::vector<double>& clock = find("clock", 3);
  next_ = static_cast<std::int64_t>(clock[0]);
  gas_steps_ = static_cast<std::int64_t>(clock[1]);
  gas_time_ = clock[2];
}

GasFrame GasCoupling::frame() const {
  const GasGrid<2>& g = gas_.grid();
  GasFrame f;
  f.nx = g.cells[0];
  f.ny = g.cells[1];
  f.x0 = g.origin[0];
  f.y0 = g.origin[1];
  f.h = g.h;
  const std::size_t n = g.interior_cells();
  f.density.reserve(n);
  f.velocity.reserve(2 * n);
  f.pressure.reserve(n);
  f.solid.reserve(n);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int j = 0; j < f.ny; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const bool solid = gas_.solid({i, j});
      const GasPrimitive<2> w = gas_.primitive({i, j});
      f.density.push_back(solid ? nan : w.rho);
      f.velocity.insert(f.velocity.end(), {solid ? nan : w.u[0], solid ? nan : w.u[1]});
      f.pressure.push_back(solid ? nan : w.p);
      f.solid.push_back(solid ? 1 : 0);
    }
  return f;
}

GasFigures GasCoupling::figures(const std::function<double(std::size_t)>& work_of) const {
  GasFigures f;
  f.gas_steps = gas_steps_;
  f.gas_time = gas_time_;
  const GasTotals<2> t = gas_.totals();
  const GasExchange<2>& x = gas_.exchange();
  f.mass = depth_ * t.mass;
  f.energy = depth_ * t.energy;
  f.inflow_energy = depth_ * x.inflow.energy;
  f.wall_work = depth_ * x.wall_work;
  f.solid_work = depth_ * x.solid_work;
  f.lost_energy = depth_ * x.lost.energy;
  double load_work_total = 0;
  for (const Outline& o : coupled_)
    if (o.load >= 0) load_work_total += work_of(static_cast<std::size_t>(o.load));
  f.coupling_error = load_work_total - f.wall_work - f.solid_work;
  const GasGrid<2>& grid = gas_.grid();
  for (const GasSpec::Probe& p : spec_.probes) {
    const std::array<int, 2> cell{
        std::clamp(static_cast<int>(std::floor((p.at[0] - grid.origin[0]) / grid.h)), 0,
                   grid.cells[0] - 1),
        std::clamp(static_cast<int>(std::floor((p.at[1] - grid.origin[1]) / grid.h)), 0,
                   grid.cells[1] - 1)};
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const bool inside = gas_.solid(cell);
    const GasPrimitive<2> w = gas_.primitive(cell);
    f.probe_p.push_back(inside ? nan : w.p);
    f.probe_rho.push_back(inside ? nan : w.rho);
  }
  return f;
}

}  // namespace mpsolid
