#include "src/solver/part_cut.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "src/solver/part_setup.hpp"
#include "src/solver/setup.hpp"

namespace mpsolid {

namespace {
constexpr const char* kAxisNames[3] = {"x", "y", "z"};

double coordinate(const Point3& p, int axis) {
  return axis == 0 ? p.x : axis == 1 ? p.y : p.z;
}

// What one pass over the sites finds: the case's box, and per body the axis
// its fill advances along last (its coordinate never falls in fill order:
// rows along x in the plane advance along y), with the coordinates of the
// sites where the slabs cut it.
struct Survey {
  std::array<double, 3> lo{}, hi{};
  std::vector<int> slow_axis;                 // per body; -1: none found
  std::vector<std::array<double, 3>> cut_at;  // per slab cut inside a body
  std::vector<std::size_t> cut_body;          // that body
};

Survey survey(const CaseSpec& spec, const BodyLayout& layout, const Decomposition& slabs) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Survey s;
  s.lo = {inf, inf, inf};
  s.hi = {-inf, -inf, -inf};
  s.slow_axis.assign(spec.bodies.size(), -1);
  std::vector<std::size_t> cuts;  // slab starts inside a body
  for (std::size_t r = 1; r + 1 < slabs.starts.size(); ++r) cuts.push_back(slabs.starts[r]);
  for (const std::size_t b : layout.order) {
    const Range range = layout.range[b];
    std::array<bool, 3> rising{true, true, true};
    std::array<double, 3> first{}, last{};
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
      for (int a = 0; a < 3; ++a) {
        const double c = coordinate(at, a);
        s.lo[a] = std::min(s.lo[a], c);
        s.hi[a] = std::max(s.hi[a], c);
        if (k == 0) first[a] = c;
        if (k > 0 && c < last[a]) rising[a] = false;
        last[a] = c;
      }
      const std::size_t g = range.begin + k;
      if (k > 0 && std::binary_search(cuts.begin(), cuts.end(), g)) {
        s.cut_at.push_back({at.x, at.y, at.z});
        s.cut_body.push_back(b);
      }
    });
    double span = -1;
    for (int a = 0; a < spec.dimension; ++a)
      if (rising[a] && last[a] - first[a] > span) {
        span = last[a] - first[a];
        s.slow_axis[b] = a;
      }
  }
  return s;
}
}  // namespace

CaseCut cut_case(const CaseSpec& spec, int ranks, CutChoice choice) {
  CaseCut out;
  out.decomposition = decompose_case(spec, ranks);
  out.kind = "slabs";
  if (ranks < 2 || spec.contact.enabled) return out;
  const BodyLayout layout = body_layout(spec);
  if (layout.total == 0) return out;
  const double reach = bond_reach(spec);
  const Survey s = survey(spec, layout, out.decomposition);
  // Bands along the longest extent, over bins a quarter of l0 wide.
  int axis = 0;
  for (int a = 1; a < spec.dimension; ++a)
    if (s.hi[a] - s.lo[a] > s.hi[axis] - s.lo[axis]) axis = a;
  const double width = 0.25 * spec.l0, lo = s.lo[axis];
  const auto bins = static_cast<std::size_t>(std::floor((s.hi[axis] - lo) / width)) + 1;
  const auto bin_of = [&](double c) {
    return std::min(bins - 1,
                    static_cast<std::size_t>(std::max(0.0, std::floor((c - lo) / width))));
  };
  std::vector<double> count(bins, 0.0);
  // The slabs' halo: each cut inside a body, a plane across the axis its
  // fill advances along, holds the body's sites within reach of it.
  double slab_ghosts = 0;
  for (const std::size_t b : layout.order) {
    std::vector<double> planes;
    const int slow = s.slow_axis[b];
    for (std::size_t c = 0; c < s.cut_body.size(); ++c)
      if (s.cut_body[c] == b && slow >= 0)
        planes.push_back(s.cut_at[c][static_cast<std::size_t>(slow)]);
    visit_body_sites(spec, b, [&](std::size_t, const Point3& at) {
      count[bin_of(coordinate(at, axis))] += 1;
      for (const double plane : planes)
        if (std::abs(coordinate(at, slow) - plane) <= reach) slab_ghosts += 1;
    });
  }
  // The bands: their first bins, nearest an equal share of the sites each.
  std::vector<std::size_t> first_bin(static_cast<std::size_t>(ranks) + 1, bins);
  first_bin[0] = 0;
  {
    double before = 0;  // sites in the bins before bin k
    std::size_t k = 0;
    for (int r = 1; r < ranks; ++r) {
      const double target = static_cast<double>(layout.total) * r / ranks;
      while (k < bins && before + count[k] <= target) before += count[k++];
      if (k < bins && target - before > before + count[k] - target) before += count[k++];
      first_bin[static_cast<std::size_t>(r)] =
          std::max(first_bin[static_cast<std::size_t>(r) - 1], k);
    }
  }
  double band_ghosts = 0;
  const auto reach_bins = static_cast<std::size_t>(std::ceil(reach / width));
  for (int r = 1; r < ranks; ++r) {
    const std::size_t edge = first_bin[static_cast<std::size_t>(r)];
    if (edge == 0 || edge >= bins) continue;
    for (std::size_t k = edge > reach_bins ? edge - reach_bins : 0;
         k < std::min(bins, edge + reach_bins); ++k)
      band_ghosts += count[k];
  }
  out.slab_ghosts = slab_ghosts;
  out.band_ghosts = band_ghosts;
  // Both estimates are reported, whichever cut is taken.
  const bool bands = choice == CutChoice::bands ||
                     (choice == CutChoice::automatic && band_ghosts < 0.8 * slab_ghosts);
  if (!bands) return out;
  // Each site's band, a body kept whole in its first site's; the pieces
  // are the runs of one band in storage order.
  const std::vector<bool> whole = bodies_kept_whole(spec, ranks);
  const auto band_of = [&](double c) {
    const std::size_t bin = bin_of(c);
    return static_cast<int>(std::upper_bound(first_bin.begin() + 1, first_bin.end() - 1, bin) -
                            (first_bin.begin() + 1));
  };
  std::vector<std::size_t> starts;
  std::vector<int> owners;
  for (const std::size_t b : layout.order) {
    int body_band = -1;
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
      int band = body_band >= 0 ? body_band : band_of(coordinate(at, axis));
      if (whole[b] && k == 0) body_band = band;
      if (owners.empty() || owners.back() != band) {
        starts.push_back(layout.range[b].begin + k);
        owners.push_back(band);
      }
    });
  }
  starts.push_back(layout.total);
  out.decomposition = decomposition_in_pieces(std::move(starts), std::move(owners), ranks);
  out.kind = std::string("bands along ") + kAxisNames[axis];
  return out;
}

}  // namespace mpsolid
