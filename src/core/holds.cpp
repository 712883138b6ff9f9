#include "src/core/holds.hpp"

#include <algorithm>

namespace mpsolid {

void clear_held_forces(ParticleStore& p, const std::vector<HeldRange>& holds, Range block) {
  for (const HeldRange& h : holds) {
    const std::size_t end = std::min(h.range.end, block.end);
    for (std::size_t i = std::max(h.range.begin, block.begin); i < end; ++i) {
      if (h.x) p.fx[i] = 0.0;
      if (h.y) p.fy[i] = 0.0;
      if (h.z) p.fz[i] = 0.0;
    }
  }
}

}  // namespace mpsolid
