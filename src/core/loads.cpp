#include "src/core/loads.hpp"

#include <algorithm>

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

PressureSurface make_pressure_surface(const Surface& surface,
                                      const std::vector<std::uint32_t>& segments, std::size_t first,
                                      double pressure, double depth) {
  PressureSurface ps;
  ps.pressure = pressure;
  ps.depth = depth;
  // The nodes the segments need, numbered in surface order.
  std::vector<std::int64_t> node_of(surface.nodes(), -1);
  for (const std::uint32_t k : segments) node_of[k] = node_of[surface.next[k]] = 0;
  for (std::size_t k = 0; k < surface.nodes(); ++k) {
    if (node_of[k] < 0) continue;
    node_of[k] = static_cast<std::int64_t>(ps.nodes());
    for (std::uint32_t w = surface.offsets[k]; w < surface.offsets[k + 1]; ++w) {
      ps.particle.push_back(static_cast<std::uint32_t>(first + surface.site[w]));
      ps.weight.push_back(surface.weight[w]);
    }
    ps.offsets.push_back(static_cast<std::uint32_t>(ps.particle.size()));
  }
  for (const std::uint32_t k : segments) {
    ps.from.push_back(static_cast<std::uint32_t>(node_of[k]));
    ps.to.push_back(static_cast<std::uint32_t>(node_of[surface.next[k]]));
  }
  ps.targets = ps.particle;
  std::sort(ps.targets.begin(), ps.targets.end());
  ps.targets.erase(std::unique(ps.targets.begin(), ps.targets.end()), ps.targets.end());
  for (const std::uint32_t i : ps.particle)
    ps.slot.push_back(static_cast<std::uint32_t>(
        std::lower_bound(ps.targets.begin(), ps.targets.end(), i) - ps.targets.begin()));
  for (std::uint32_t k = 0; k < ps.nodes(); ++k) ps.hosted.push_back(k);
  for (auto* v : {&ps.x, &ps.y, &ps.fx, &ps.fy}) v->assign(ps.nodes(), 0.0);
  ps.target_fx.assign(ps.targets.size(), 0.0);
  ps.target_fy.assign(ps.targets.size(), 0.0);
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
  s.target_fx.assign(s.targets.size(), 0.0);
  s.target_fy.assign(s.targets.size(), 0.0);
  return s;
}

namespace {
// Node k's position in the current state.
Point2 node_now(const ParticleStore& p, const PressureSurface& s, std::size_t k) {
  return affine_point(s.offsets, s.particle, s.weight, k, p.x.data(), p.y.data(), 0);
}

// The work of the running step's node forces from its start to now (the
// whole state: every node's particles at hand).
double running_pressure_work(const ParticleStore& p, const PressureSurface& s) {
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    const Point2 now = node_now(p, s, k);
    work += s.fx[k] * (now.x - s.x[k]) + s.fy[k] * (now.y - s.y[k]);
  }
  return work;
}

// A pressure load at the start of a step, once its nodes' start positions
// (nx, ny) are known: the previous step's work (as running_pressure_work
// sums it), the positions and this step's forces.
void activate_pressure(StepLoad& load, const std::vector<double>& nx, const std::vector<double>& ny,
                       double time) {
  PressureSurface& s = load.surface;
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    work += s.fx[k] * (nx[k] - s.x[k]) + s.fy[k] * (ny[k] - s.y[k]);
    s.x[k] = nx[k];
    s.y[k] = ny[k];
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
  std::vector<std::vector<double>> nx(loads.size()), ny(loads.size());
  std::vector<double> mine;  // (load, node, x, y) of the hosted nodes
  bool any = false;
  for (std::size_t l = 0; l < loads.size(); ++l) {
    const StepLoad& load = loads[l];
    if (!load.is_pressure() || step < load.first_step) continue;
    any = true;
    nx[l].assign(load.surface.nodes(), 0.0);
    ny[l].assign(load.surface.nodes(), 0.0);
    for (const std::uint32_t k : load.surface.hosted) {
      const Point2 now = node_now(p, load.surface, k);
      nx[l][k] = now.x;
      ny[l][k] = now.y;
      if (gather)
        mine.insert(mine.end(), {static_cast<double>(l), static_cast<double>(k), now.x, now.y});
    }
  }
  if (!any) return;
  if (gather) {
    const std::vector<double> all = (*gather)(mine);
    for (std::size_t at = 0; at + 4 <= all.size(); at += 4) {
      const auto l = static_cast<std::size_t>(all[at]), k = static_cast<std::size_t>(all[at + 1]);
      nx[l][k] = all[at + 2];
      ny[l][k] = all[at + 3];
    }
  }
  for (std::size_t l = 0; l < loads.size(); ++l)
    if (!nx[l].empty())
      activate_pressure(loads[l], nx[l], ny[l], static_cast<double>(step) * dt - loads[l].start);
}
}  // namespace

void pressure_forces(StepLoad& load) {
  PressureSurface& s = load.surface;
  std::fill(s.fx.begin(), s.fx.end(), 0.0);
  std::fill(s.fy.begin(), s.fy.end(), 0.0);
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
  std::fill(s.target_fx.begin(), s.target_fx.end(), 0.0);
  std::fill(s.target_fy.begin(), s.target_fy.end(), 0.0);
  for (std::size_t k = 0; k < s.nodes(); ++k)
    for (std::uint32_t w = s.offsets[k]; w < s.offsets[k + 1]; ++w) {
      if (s.slot[w] == PressureSurface::kElsewhere) continue;  // another part's particle
      s.target_fx[s.slot[w]] += s.weight[w] * s.fx[k];
      s.target_fy[s.slot[w]] += s.weight[w] * s.fy[k];
    }
}

void close_running_step(const ParticleStore& p, StepLoad& load) {
  if (!load.active) return;
  PressureSurface& s = load.surface;
  load.work += running_pressure_work(p, s);
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    const Point2 now = node_now(p, s, k);
    s.x[k] = now.x;
    s.y[k] = now.y;
  }
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
