#pragma once
// Contact between particles that are not bonded in the reference
// configuration (MODEL.md section 8): the candidates (surface particles of
// the contacting bodies, fixed at set-up), their Verlet list and the contact
// forces of the current step. Plain data: the search that fills the list is
// neighbor/contact_search, the force pass kernels/contact_force.
//
// The forces never depend on when the list was built: a particle sums the
// pairs closer than the contact distance, in ascending partner index, and
// every such pair is in any list that is still valid (no candidate has moved
// more than half the skin since the build). So rebuilds, resumes and thread
// counts leave the bits alone.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <vector>

#include "src/core/particle_store.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

struct ContactParameters {
  double distance = 0;   // d (m): the pair force is zero at and beyond it
  double stiffness = 0;  // k (N/m over the depth): force k (d - r) along the pair
  double skin = 0;       // Verlet skin (m): the list holds pairs closer than d + skin
  // The interpenetration check's distance (m): a pair closer stops the run.
  double min_distance = 0;
};

// Candidates that never move relative to each other share a group (all walls
// one, each rigid body its own) and are never paired; elastic ones have none.
inline constexpr std::int32_t kNoContactGroup = -1;

// A step some thread marked in the contact pass (the list found stale, a
// pair found too close), read after the pass's barrier or after the team.
// A step number rather than a flag, so that no thread has to clear it while
// another may still read it. Copyable, so the solver state stays a value.
struct StepMark {
  std::atomic<std::int64_t> step{-1};
  StepMark() = default;
  StepMark(const StepMark& o) : step(o.step.load()) {}
  StepMark& operator=(const StepMark& o) {
    step.store(o.step.load());
    return *this;
  }
};

struct ContactState {
  ContactParameters parameters;
  // Storage indices of the candidates, ascending, and each one's group.
  std::vector<std::uint32_t> candidates;
  std::vector<std::int32_t> group;
  // Candidates [0, first_moving) are walls: their forces are never needed.
  std::size_t first_moving = 0;
  // The Verlet list, both directions: candidate c's partners (storage
  // indices, ascending) are partner[offsets[c] .. offsets[c + 1]).
  std::vector<std::uint32_t> offsets;
  std::vector<std::uint32_t> partner;
  // Candidate positions when the list was built (z in space only).
  std::vector<double> built_x, built_y, built_z;
  std::int64_t rebuilds = 0;
  StepMark stale;
  // The first step in which a pair came closer than min_distance (-1: none
  // yet): the blow-up check, run every few hundred steps, reports it.
  StepMark too_close;
  // The current step's contact force on each candidate (N over the depth;
  // z in space only).
  std::vector<double> force_x, force_y, force_z;

  // The forces' arrays, one per candidate and axis, zeroed.
  void zero_forces(int dimension) {
    force_x.assign(size(), 0.0);
    force_y.assign(size(), 0.0);
    if (dimension == 3) force_z.assign(size(), 0.0);
  }

  bool enabled() const { return !candidates.empty(); }
  std::size_t size() const { return candidates.size(); }
  // True when candidate a has moved more than half the skin since the
  // build: a pair closer than d might then be missing from the list. (A
  // little less than half, so rounding in the test never lets one through.
  // A position that is not finite has not "moved": no rebuild can help it,
  // and the run's finite check stops the run.)
  bool moved_past_half_skin(const ParticleStore& p, std::size_t a) const {
    const double dx = p.x[candidates[a]] - built_x[a];
    const double dy = p.y[candidates[a]] - built_y[a];
    double d2 = dx * dx + dy * dy;
    if (!built_z.empty()) {
      const double dz = p.z[candidates[a]] - built_z[a];
      d2 += dz * dz;
    }
    const double half = 0.4999 * parameters.skin;
    return d2 > half * half;
  }
  // The candidates whose storage index lies in [block.begin, block.end)
  // (their storage indices ascending).
  Range candidates_in(Range block) const {
    const auto first = std::lower_bound(candidates.begin(), candidates.end(), block.begin);
    const auto last = std::lower_bound(first, candidates.end(), block.end);
    return {static_cast<std::size_t>(first - candidates.begin()),
            static_cast<std::size_t>(last - candidates.begin())};
  }

  // On a rank's part cut in pieces, which stores the ghosts beside its own
  // particles after them, the candidates (in the run's storage order) do
  // not ascend in storage index here: then `by_storage` lists them in
  // ascending storage index (empty where they ascend).
  std::vector<std::uint32_t> by_storage;
  void order_by_storage() {
    by_storage.clear();
    if (std::is_sorted(candidates.begin(), candidates.end())) return;
    by_storage.resize(size());
    for (std::size_t a = 0; a < size(); ++a) by_storage[a] = static_cast<std::uint32_t>(a);
    std::sort(by_storage.begin(), by_storage.end(),
              [&](std::uint32_t a, std::uint32_t b) { return candidates[a] < candidates[b]; });
  }
  // Calls f(a) for each candidate a whose storage index lies in block.
  template <class F>
  void for_candidates_in(Range block, F&& f) const {
    if (by_storage.empty()) {
      const Range r = candidates_in(block);
      for (std::size_t a = r.begin; a < r.end; ++a) f(a);
      return;
    }
    const auto at = [&](std::size_t i) {
      return std::lower_bound(by_storage.begin(), by_storage.end(), i,
                              [&](std::uint32_t a, std::size_t v) { return candidates[a] < v; });
    };
    for (auto k = at(block.begin), end = at(block.end); k != end; ++k) f(*k);
  }
};

}  // namespace mpsolid
