#include "src/holds.hpp"

#include "src/parallel.hpp"

namespace mpsolid {

void clear_held_forces(ParticleStore& p, const std::vector<HeldRange>& holds) {
  for (const HeldRange& h : holds)
    parallel_for(h.range.begin, h.range.end, [&](std::size_t i) {
      if (h.x) p.fx[i] = 0.0;
      if (h.y) p.fy[i] = 0.0;
    });
}

}  // namespace mpsolid
