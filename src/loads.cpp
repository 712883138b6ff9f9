#include "src/loads.hpp"

#include "src/ordered_sum.hpp"
#include "src/parallel.hpp"

namespace mpsolid {

void centroid(const ParticleStore& p, Range range, double& cx, double& cy) {
  const auto [sx, sy] = ordered_sum<2>(range.begin, range.end, [&](std::size_t i) {
    return std::array<double, 2>{p.x[i], p.y[i]};
  });
  cx = sx / static_cast<double>(range.size());
  cy = sy / static_cast<double>(range.size());
}

void apply_loads(ParticleStore& p, std::vector<StepLoad>& loads, std::int64_t step) {
  for (StepLoad& load : loads) {
    if (step < load.first_step) continue;
    if (!load.active) {
      centroid(p, load.range, load.cx_on, load.cy_on);
      load.active = true;
    }
    const double share = 1.0 / static_cast<double>(load.range.size());
    const double fx = load.fx * share, fy = load.fy * share;
    parallel_for(load.range.begin, load.range.end, [&](std::size_t i) {
      p.fx[i] += fx;
      p.fy[i] += fy;
    });
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
