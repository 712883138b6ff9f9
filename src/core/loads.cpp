#include "src/core/loads.hpp"

#include <algorithm>
#include <stdexcept>

#include "src/core/ordered_sum.hpp"

namespace mpsolid {

void centroid(const ParticleStore& p, Range range, double& cx, double& cy) {
  const auto [sx, sy] = ordered_sum<2>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 2>{p.x[i], p.y[i]};
  });
  cx = sx / static_cast<double>(range.size());
  cy = sy / static_cast<double>(range.size());
}

void centroid(const ParticleStore& p, Range range, double& cx, double& cy, double& cz) {
  cz = 0.0;
  if (p.dimension != 3) return centroid(p, range, cx, cy);
  const auto [sx, sy, sz] = ordered_sum<3>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 3>{p.x[i], p.y[i], p.z[i]};
  });
  const auto n = static_cast<double>(range.size());
  cx = sx / n;
  cy = sy / n;
  cz = sz / n;
}

namespace {
// F . (c - c0) for a force and the centroid's move (z only where it moves).
double force_work(const StepLoad& load, double dx, double dy, double dz) {
  const double plane = load.fx * dx + load.fy * dy;
  return dz == 0.0 && load.fz == 0.0 ? plane : plane + load.fz * dz;
}
}  // namespace

namespace {
// The nodes of `surface` that `used` marks, numbered in surface order, with
// their weights over storage indices `first` + site, into `ps`; returns each
// surface node's number there (-1 where unused).
template <class AnySurface>
std::vector<std::int64_t> take_nodes(const AnySurface& surface, const std::vector<bool>& used,
                                     std::size_t first, PressureSurface& ps) {
  std::vector<std::int64_t> node_of(surface.nodes(), -1);
  for (std::size_t k = 0; k < surface.nodes(); ++k) {
    if (!used[k]) continue;
    node_of[k] = static_cast<std::int64_t>(ps.nodes());
    for (std::uint32_t w = surface.offsets[k]; w < surface.offsets[k + 1]; ++w) {
      ps.particle.push_back(static_cast<std::uint32_t>(first + surface.site[w]));
      ps.weight.push_back(surface.weight[w]);
    }
    ps.offsets.push_back(static_cast<std::uint32_t>(ps.particle.size()));
  }
  return node_of;
}

// The particles the nodes reach, each weight's place among them, every node
// hosted, and the running step's arrays.
void finish_pressure_surface(PressureSurface& ps) {
  ps.targets = ps.particle;
  std::sort(ps.targets.begin(), ps.targets.end());
  ps.targets.erase(std::unique(ps.targets.begin(), ps.targets.end()), ps.targets.end());
  for (const std::uint32_t i : ps.particle)
    ps.slot.push_back(static_cast<std::uint32_t>(
        std::lower_bound(ps.targets.begin(), ps.targets.end(), i) - ps.targets.begin()));
  for (std::uint32_t k = 0; k < ps.nodes(); ++k) ps.hosted.push_back(k);
  for (auto* v : {&ps.x, &ps.y}) v->assign(ps.nodes(), 0.0);
  if (ps.in_space()) ps.z.assign(ps.nodes(), 0.0);
  ps.size_forces();
}
}  // namespace

PressureSurface make_pressure_surface(const Surface& surface,
                                      const std::vector<std::uint32_t>& segments, std::size_t first,
                                      double pressure, double depth) {
  PressureSurface ps;
  ps.pressure = pressure;
  ps.depth = depth;
  std::vector<bool> used(surface.nodes(), false);
  for (const std::uint32_t k : segments) used[k] = used[surface.next[k]] = true;
  const std::vector<std::int64_t> node_of = take_nodes(surface, used, first, ps);
  for (const std::uint32_t k : segments) {
    ps.from.push_back(static_cast<std::uint32_t>(node_of[k]));
    ps.to.push_back(static_cast<std::uint32_t>(node_of[surface.next[k]]));
  }
  finish_pressure_surface(ps);
  return ps;
}

PressureSurface make_pressure_surface3(const Surface3& surface,
                                       const std::vector<std::uint32_t>& quads, std::size_t first,
                                       double pressure) {
  PressureSurface ps;
  ps.pressure = pressure;
  ps.depth = 1.0;
  std::vector<bool> used(surface.nodes(), false);
  for (const std::uint32_t q : quads)
    for (int c = 0; c < 4; ++c) used[surface.corner[4 * q + c]] = true;
  const std::vector<std::int64_t> node_of = take_nodes(surface, used, first, ps);
  for (const std::uint32_t q : quads)
    for (int c = 0; c < 4; ++c)
      ps.quad.push_back(static_cast<std::uint32_t>(node_of[surface.corner[4 * q + c]]));
  finish_pressure_surface(ps);
  return ps;
}

PressureSurface local_pressure_surface(const PressureSurface& whole,
                                       const std::function<std::uint32_t(std::uint32_t)>& local_of,
                                       const std::function<bool(std::uint32_t)>& owned) {
  constexpr std::uint32_t elsewhere = PressureSurface::kElsewhere;
  PressureSurface s = whole;
  s.hosted.clear();
  s.targets.clear();
  for (std::uint32_t& i : s.particle) i = local_of(i);
  for (std::uint32_t k = 0; k < s.nodes(); ++k) {
    // The host's lattice neighbours are its bond partners: held wherever it is owned.
    const std::uint32_t host = s.particle[s.offsets[k]];
    if (host != elsewhere && owned(host)) s.hosted.push_back(k);
  }
  for (const std::uint32_t i : s.particle)
    if (i != elsewhere && owned(i)) s.targets.push_back(i);
  std::sort(s.targets.begin(), s.targets.end());
  s.targets.erase(std::unique(s.targets.begin(), s.targets.end()), s.targets.end());
  s.slot.clear();
  for (const std::uint32_t i : s.particle) {
    const auto at = std::lower_bound(s.targets.begin(), s.targets.end(), i);
    s.slot.push_back(at != s.targets.end() && *at == i
                         ? static_cast<std::uint32_t>(at - s.targets.begin())
                         : elsewhere);
  }
  s.size_target_forces();
  return s;
}

namespace {
// Node k's position in the current state (z only in space).
struct NodePosition {
  double x = 0, y = 0, z = 0;
};
NodePosition node_now(const ParticleStore& p, const PressureSurface& s, std::size_t k) {
  const Point2 plane = affine_point(s.offsets, s.particle, s.weight, k, p.x.data(), p.y.data(), 0);
  NodePosition at{plane.x, plane.y, 0.0};
  if (s.in_space())
    for (std::uint32_t w = s.offsets[k]; w < s.offsets[k + 1]; ++w)
      at.z += s.weight[w] * p.z[s.particle[w]];
  return at;
}

// The work of node k's force in the running step as it moves to `now`.
double node_work(const PressureSurface& s, std::size_t k, const NodePosition& now) {
  const double plane = s.fx[k] * (now.x - s.x[k]) + s.fy[k] * (now.y - s.y[k]);
  return s.in_space() ? plane + s.fz[k] * (now.z - s.z[k]) : plane;
}

// The work of the running step's node forces from its start to now (the
// whole state: every node's particles at hand).
double running_pressure_work(const ParticleStore& p, const PressureSurface& s) {
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) work += node_work(s, k, node_now(p, s, k));
  return work;
}

// Makes `at` node k's position at the start of the running step.
void start_node(PressureSurface& s, std::size_t k, const NodePosition& at) {
  s.x[k] = at.x;
  s.y[k] = at.y;
  if (s.in_space()) s.z[k] = at.z;
}

// A pressure load at the start of a step, once its nodes' start positions
// are known: the previous step's work (as running_pressure_work sums it),
// the positions and this step's forces.
void activate_pressure(StepLoad& load, const std::vector<NodePosition>& at, double time) {
  PressureSurface& s = load.surface;
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    work += node_work(s, k, at[k]);
    start_node(s, k, at[k]);
  }
  if (load.active) load.work += work;
  load.active = true;
  if (!load.history.constant()) load.factor = load.history.factor(time);
  pressure_forces(load);
}

// The pressure loads on at `step`: each part positions its hosted nodes,
// the parts share them (with `gather`), and every part activates each load
// with every node.
void activate_pressures(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                        double dt, const GatherParts* gather) {
  std::vector<std::vector<NodePosition>> at(loads.size());
  // (load, node, x, y[, z]) of the hosted nodes.
  const std::size_t stride = p.dimension == 3 ? 5 : 4;
  std::vector<double> mine;
  bool any = false;
  for (std::size_t l = 0; l < loads.size(); ++l) {
    const StepLoad& load = loads[l];
    if (!load.is_pressure() || step < load.first_step) continue;
    any = true;
    at[l].assign(load.surface.nodes(), {});
    for (const std::uint32_t k : load.surface.hosted) {
      const NodePosition now = node_now(p, load.surface, k);
      at[l][k] = now;
      if (!gather) continue;
      mine.insert(mine.end(), {static_cast<double>(l), static_cast<double>(k), now.x, now.y});
      if (stride == 5) mine.push_back(now.z);
    }
  }
  if (!any) return;
  if (gather) {
    const std::vector<double> all = (*gather)(mine);
    for (std::size_t from = 0; from + stride <= all.size(); from += stride) {
      const auto l = static_cast<std::size_t>(all[from]);
      const auto k = static_cast<std::size_t>(all[from + 1]);
      at[l][k] = {all[from + 2], all[from + 3], stride == 5 ? all[from + 4] : 0.0};
    }
  }
  for (std::size_t l = 0; l < loads.size(); ++l)
    if (!at[l].empty())
      activate_pressure(loads[l], at[l], static_cast<double>(step) * dt - loads[l].start);
}
}  // namespace

void pressure_forces(StepLoad& load) {
  PressureSurface& s = load.surface;
  std::fill(s.fx.begin(), s.fx.end(), 0.0);
  std::fill(s.fy.begin(), s.fy.end(), 0.0);
  std::fill(s.fz.begin(), s.fz.end(), 0.0);
  if (!s.given_fx.empty()) {
    s.fx = s.given_fx;
    s.fy = s.given_fy;
  }
  // -p D R(x_to - x_from) on each segment, R the clockwise quarter turn (the
  // outward area vector), half to each end.
  const double half = -0.5 * load.factor * s.pressure * s.depth;
  for (std::size_t g = 0; g < s.from.size() && s.given_fx.empty(); ++g) {
    const std::uint32_t a = s.from[g], b = s.to[g];
    const double fx = half * (s.y[b] - s.y[a]), fy = -half * (s.x[b] - s.x[a]);
    s.fx[a] += fx;
    s.fy[a] += fy;
    s.fx[b] += fx;
    s.fy[b] += fy;
  }
  // In space, -p times each node's share of its quadrilaterals' area vectors.
  if (s.in_space() && s.given_fx.empty())
    add_node_area_vectors(s.quad, {s.x.data(), s.y.data(), s.z.data()}, -load.factor * s.pressure,
                          {s.fx.data(), s.fy.data(), s.fz.data()});
  std::fill(s.target_fx.begin(), s.target_fx.end(), 0.0);
  std::fill(s.target_fy.begin(), s.target_fy.end(), 0.0);
  std::fill(s.target_fz.begin(), s.target_fz.end(), 0.0);
  for (std::size_t k = 0; k < s.nodes(); ++k)
    for (std::uint32_t w = s.offsets[k]; w < s.offsets[k + 1]; ++w) {
      if (s.slot[w] == PressureSurface::kElsewhere) continue;  // another part's particle
      s.target_fx[s.slot[w]] += s.weight[w] * s.fx[k];
      s.target_fy[s.slot[w]] += s.weight[w] * s.fy[k];
      if (s.in_space()) s.target_fz[s.slot[w]] += s.weight[w] * s.fz[k];
    }
}

void append_hosted_node_positions(const ParticleStore& p, const std::vector<StepLoad>& loads,
                                  std::vector<double>& out) {
  std::size_t ordinal = 0;
  for (const StepLoad& load : loads) {
    if (!load.is_pressure()) continue;
    if (load.active)
      for (const std::uint32_t k : load.surface.hosted) {
        const NodePosition at = node_now(p, load.surface, k);
        out.insert(out.end(),
                   {static_cast<double>(ordinal), static_cast<double>(k), at.x, at.y, at.z});
      }
    ++ordinal;
  }
}

double pressure_work_at(const StepLoad& load, const std::vector<double>& xyz) {
  if (!load.active) return 0.0;
  const PressureSurface& s = load.surface;
  if (xyz.size() != 3 * s.nodes())
    throw std::logic_error("pressure_work_at: not every node's position");
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k)
    work += node_work(s, k, {xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]});
  return load.work + work;
}

void close_running_step_at(StepLoad& load, const std::vector<double>& xyz) {
  if (!load.active) return;
  load.work = pressure_work_at(load, xyz);
  PressureSurface& s = load.surface;
  for (std::size_t k = 0; k < s.nodes(); ++k)
    start_node(s, k, {xyz[3 * k], xyz[3 * k + 1], xyz[3 * k + 2]});
}

bool any_pressure(const std::vector<StepLoad>& loads) {
  return std::any_of(loads.begin(), loads.end(), [](const StepLoad& l) { return l.is_pressure(); });
}

void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                    double dt, const GatherParts* gather) {
  activate_pressures(p, loads, step, dt, gather);
  for (StepLoad& load : loads) {
    if (step < load.first_step || load.is_pressure()) continue;
    const bool varying = !load.history.constant();
    if (!load.active) {
      centroid(p, load.range, load.cx_on, load.cy_on, load.cz_on);
      load.active = true;
      if (!varying) continue;
      load.cx_last = load.cx_on;
      load.cy_last = load.cy_on;
      load.cz_last = load.cz_on;
    } else if (varying) {
      // The work of the step that just ran: its force times the centroid's move.
      double cx = 0, cy = 0, cz = 0;
      centroid(p, load.range, cx, cy, cz);
      load.work +=
          load.factor * force_work(load, cx - load.cx_last, cy - load.cy_last, cz - load.cz_last);
      load.cx_last = cx;
      load.cy_last = cy;
      load.cz_last = cz;
    }
    if (varying) load.factor = load.history.factor(static_cast<double>(step) * dt - load.start);
  }
}

void apply_loads(ParticleStore& p, const std::vector<StepLoad>& loads, Range block) {
  for (const StepLoad& load : loads) {
    if (!load.active) continue;
    if (load.is_pressure()) {
      const PressureSurface& s = load.surface;
      const auto first = std::lower_bound(s.targets.begin(), s.targets.end(), block.begin);
      for (auto it = first; it != s.targets.end() && *it < block.end; ++it) {
        const std::size_t t = static_cast<std::size_t>(it - s.targets.begin());
        p.fx[*it] += s.target_fx[t];
        p.fy[*it] += s.target_fy[t];
        if (s.in_space()) p.fz[*it] += s.target_fz[t];
      }
      continue;
    }
    const double share = 1.0 / static_cast<double>(load.range.size());
    // A step's factor stays 1, and 1 x F is F: its shares keep the bits of F / N.
    const double fx = load.factor * load.fx * share, fy = load.factor * load.fy * share;
    const std::size_t b = std::max(block.begin, load.range.begin);
    const std::size_t e = std::min(block.end, load.range.end);
    for (std::size_t i = b; i < e; ++i) {
      p.fx[i] += fx;
      p.fy[i] += fy;
    }
    if (p.dimension == 3) {
      const double fz = load.factor * load.fz * share;
      for (std::size_t i = b; i < e; ++i) p.fz[i] += fz;
    }
  }
}

double load_work(const ParticleStore& p, const StepLoad& load) {
  if (!load.active) return 0.0;
  if (load.is_pressure()) return load.work + running_pressure_work(p, load.surface);
  double cx = 0, cy = 0, cz = 0;
  centroid(p, load.range, cx, cy, cz);
  if (load.history.constant())
    return force_work(load, cx - load.cx_on, cy - load.cy_on, cz - load.cz_on);
  // The steps before the last, and the last up to now.
  return load.work +
         load.factor * force_work(load, cx - load.cx_last, cy - load.cy_last, cz - load.cz_last);
}

double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads) {
  double work = 0.0;
  for (const StepLoad& load : loads) work += load_work(p, load);
  return work;
}

}  // namespace mpsolid
