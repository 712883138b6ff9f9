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

void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step,
                    double dt) {
  for (StepLoad& load : loads) {
    if (step < load.first_step) continue;
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
