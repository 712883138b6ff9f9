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

void activate_loads(const ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step) {
  for (StepLoad& load : loads) {
    if (step < load.first_step || load.active) continue;
    centroid(p, load.range, load.cx_on, load.cy_on);
    load.active = true;
  }
}

void apply_loads(ParticleStore& p, const std::vector<StepLoad>& loads, Range block) {
  for (const StepLoad& load : loads) {
    if (!load.active) continue;
    const double share = 1.0 / static_cast<double>(load.range.size());
    const double fx = load.fx * share, fy = load.fy * share;
    const std::size_t b = std::max(block.begin, load.range.begin);
    const std::size_t e = std::min(block.end, load.range.end);
    for (std::size_t i = b; i < e; ++i) {
      p.fx[i] += fx;
      p.fy[i] += fy;
    }
  }
}

double external_work(const ParticleStore& p, const std::vector<StepLoad>& loads) {
  double work = 0.0;
  for (const StepLoad& load : loads) {
    if (!load.active) continue;
    double cx = 0, cy = 0;
    centroid(p, load.range, cx, cy);
    work += load.fx * (cx - load.cx_on) + load.fy * (cy - load.cy_on);
  }
  return work;
}

}  // namespace mpsolid
