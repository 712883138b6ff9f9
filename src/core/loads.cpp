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
  for (auto* v : {&ps.x, &ps.y, &ps.fx, &ps.fy}) v->assign(ps.nodes(), 0.0);
  ps.target_fx.assign(ps.targets.size(), 0.0);
  ps.target_fy.assign(ps.targets.size(), 0.0);
  return ps;
}

void shift_particles(PressureSurface& surface, std::size_t shift) {
  for (auto* v : {&surface.particle, &surface.targets})
    for (std::uint32_t& i : *v) i = static_cast<std::uint32_t>(i - shift);
}

namespace {
// Node k's position in the current state.
Point2 node_now(const ParticleStore& p, const PressureSurface& s, std::size_t k) {
  return affine_point(s.offsets, s.particle, s.weight, k, p.x.data(), p.y.data(), 0);
}

// The work of the running step's node forces from its start to now, calling
// each(k, position) with every node's current position (computed once).
template <class Each>
double running_pressure_work(const ParticleStore& p, const PressureSurface& s, Each&& each) {
  double work = 0;
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    const Point2 now = node_now(p, s, k);
    work += s.fx[k] * (now.x - s.x[k]) + s.fy[k] * (now.y - s.y[k]);
    each(k, now);
  }
  return work;
}

// A pressure load at the start of a step: the previous step's work, the
// nodes' positions and this step's forces.
void activate_pressure(const ParticleStore& p, StepLoad& load, double time) {
  PressureSurface& s = load.surface;
  // The step's start positions are the current ones.
  const double work = running_pressure_work(p, s, [&](std::size_t k, Point2 now) {
    s.x[k] = now.x;
    s.y[k] = now.y;
  });
  if (load.active) load.work += work;
  load.active = true;
  if (!load.history.constant()) load.factor = load.history.factor(time);
  pressure_forces(load);
}
}  // namespace

void pressure_forces(StepLoad& load) {
  PressureSurface& s = load.surface;
  std::fill(s.fx.begin(), s.fx.end(), 0.0);
  std::fill(s.fy.begin(), s.fy.end(), 0.0);
  // -p D R(x_to - x_from) on each segment, R the clockwise quarter turn (the
  // outward area vector), half to each end.
  const double half = -0.5 * load.factor * s.pressure * s.depth;
  for (std::size_t g = 0; g < s.from.size(); ++g) {
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
      s.target_fx[s.slot[w]] += s.weight[w] * s.fx[k];
      s.target_fy[s.slot[w]] += s.weight[w] * s.fy[k];
    }
}

void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                    double dt) {
  for (StepLoad& load : loads) {
    if (step < load.first_step) continue;
    if (load.is_pressure()) {
      activate_pressure(p, load, static_cast<double>(step) * dt - load.start);
      continue;
    }
    const bool varying = !load.history.constant();
    if (!load.active) {
      centroid(p, load.range, load.cx_on, load.cy_on);
      load.active = true;
      if (!varying) continue;
      load.cx_last = load.cx_on;
      load.cy_last = load.cy_on;
    } else if (varying) {
      // The work of the step that just ran: its force times the centroid's move.
      double cx = 0, cy = 0;
      centroid(p, load.range, cx, cy);
      load.work += load.factor * (load.fx * (cx - load.cx_last) + load.fy * (cy - load.cy_last));
      load.cx_last = cx;
      load.cy_last = cy;
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
  }
}

double load_work(const ParticleStore& p, const StepLoad& load) {
  if (!load.active) return 0.0;
  if (load.is_pressure())
    return load.work + running_pressure_work(p, load.surface, [](std::size_t, Point2) {});
  double cx = 0, cy = 0;
  centroid(p, load.range, cx, cy);
  if (load.history.constant()) return load.fx * (cx - load.cx_on) + load.fy * (cy - load.cy_on);
  // The steps before the last, and the last up to now.
  return load.work + load.factor * (load.fx * (cx - load.cx_last) + load.fy * (cy - load.cy_last));
}

double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads) {
  double work = 0.0;
  for (const StepLoad& load : loads) work += load_work(p, load);
  return work;
}

}  // namespace mpsolid
