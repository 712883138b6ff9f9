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

// A tree of cuts over the sites. Node k covers ranks [r0, r1) and a box;
// an inner node cuts its sites across `axis` (its box's longest extent)
// at bin edges (bins a quarter of l0 wide) into children, each child a
// contiguous share of its ranks and, nearest that share, of its sites.
// Bands: the root cut into one child per rank. Blocks (recursive
// coordinate bisection): every node cut in two, its ranks halved.
struct CutNode {
  int r0 = 0, r1 = 0;
  std::array<double, 3> lo{}, hi{};
  int axis = 0;
  double origin = 0;
  std::size_t bins = 0;
  std::vector<double> count;           // its sites per bin
  std::vector<std::size_t> first_bin;  // each child's first bin, then `bins`
  std::vector<std::size_t> children;
};

class CutTree {
 public:
  CutTree(const CaseSpec& spec, const std::array<double, 3>& lo, const std::array<double, 3>& hi,
          int ranks)
      : width_(0.25 * spec.l0),
        reach_bins_(static_cast<std::size_t>(std::ceil(bond_reach(spec) / width_))),
        dimension_(spec.dimension) {
    CutNode root;
    root.r1 = ranks;
    root.lo = lo;
    root.hi = hi;
    nodes_.push_back(open(root));
  }
  // The root: binned across the case's longest extent.
  const CutNode& root() const { return nodes_.front(); }
  std::size_t bin_of(const CutNode& n, double c) const {
    return std::min(n.bins - 1,
                    static_cast<std::size_t>(std::max(0.0, std::floor((c - n.origin) / width_))));
  }
  // The node a site falls in: a leaf, or a node not cut yet.
  std::size_t node_of(const Point3& at) const {
    std::size_t k = 0;
    while (!nodes_[k].children.empty()) {
      const CutNode& n = nodes_[k];
      const std::size_t bin = bin_of(n, coordinate(at, n.axis));
      const auto child = static_cast<std::size_t>(
          std::upper_bound(n.first_bin.begin() + 1, n.first_bin.end() - 1, bin) -
          (n.first_bin.begin() + 1));
      k = n.children[child];
    }
    return k;
  }
  // Counts a site in the bins of the node it falls in, if not cut yet.
  void count(const Point3& at) {
    CutNode& n = nodes_[node_of(at)];
    if (!n.count.empty()) n.count[bin_of(n, coordinate(at, n.axis))] += 1;
  }
  // Cuts node k, its sites counted, into `parts` children (its ranks in
  // equal shares, the first ones the smaller); returns the sites within a
  // bond's reach of its cuts, the ghosts they are estimated to imply.
  double cut(std::size_t k, int parts) {
    CutNode n = std::move(nodes_[k]);
    const int ranks = n.r1 - n.r0;
    double total = 0;
    for (const double c : n.count) total += c;
    n.first_bin.assign(static_cast<std::size_t>(parts) + 1, n.bins);
    n.first_bin[0] = 0;
    std::vector<int> rank_start{n.r0};
    double before = 0;  // sites in the bins before bin b
    std::size_t b = 0;
    for (int p = 1; p < parts; ++p) {
      const int r = n.r0 + p * ranks / parts;
      rank_start.push_back(r);
      const double target = total * (r - n.r0) / ranks;
      while (b < n.bins && before + n.count[b] <= target) before += n.count[b++];
      if (b < n.bins && target - before > before + n.count[b] - target) before += n.count[b++];
      n.first_bin[static_cast<std::size_t>(p)] =
          std::max(n.first_bin[static_cast<std::size_t>(p) - 1], b);
    }
    rank_start.push_back(n.r1);
    double ghosts = 0;
    for (int p = 1; p < parts; ++p) {
      const std::size_t edge = n.first_bin[static_cast<std::size_t>(p)];
      if (edge == 0 || edge >= n.bins) continue;
      for (std::size_t i = edge > reach_bins_ ? edge - reach_bins_ : 0;
           i < std::min(n.bins, edge + reach_bins_); ++i)
        ghosts += n.count[i];
    }
    for (int p = 0; p < parts; ++p) {
      CutNode child;
      child.r0 = rank_start[static_cast<std::size_t>(p)];
      child.r1 = rank_start[static_cast<std::size_t>(p) + 1];
      child.lo = n.lo;
      child.hi = n.hi;
      const auto a = static_cast<std::size_t>(n.axis);
      child.lo[a] = std::max(
          n.lo[a],
          n.origin + width_ * static_cast<double>(n.first_bin[static_cast<std::size_t>(p)]));
      child.hi[a] = std::min(
          n.hi[a],
          n.origin + width_ * static_cast<double>(n.first_bin[static_cast<std::size_t>(p) + 1]));
      n.children.push_back(nodes_.size());
      nodes_.push_back(child.r1 - child.r0 > 1 ? open(child) : child);
    }
    n.count.clear();
    nodes_[k] = std::move(n);
    return ghosts;
  }
  // The nodes binned and not cut yet.
  std::vector<std::size_t> open_nodes() const {
    std::vector<std::size_t> out;
    for (std::size_t k = 0; k < nodes_.size(); ++k)
      if (nodes_[k].children.empty() && !nodes_[k].count.empty()) out.push_back(k);
    return out;
  }
  // A site's rank.
  int rank_of(const Point3& at) const { return nodes_[node_of(at)].r0; }

 private:
  // The node binned along its box's longest extent.
  CutNode open(CutNode n) const {
    n.axis = 0;
    for (int a = 1; a < dimension_; ++a)
      if (n.hi[static_cast<std::size_t>(a)] - n.lo[static_cast<std::size_t>(a)] >
          n.hi[static_cast<std::size_t>(n.axis)] - n.lo[static_cast<std::size_t>(n.axis)])
        n.axis = a;
    const auto a = static_cast<std::size_t>(n.axis);
    n.origin = n.lo[a];
    n.bins = static_cast<std::size_t>(std::max(0.0, std::floor((n.hi[a] - n.lo[a]) / width_))) + 1;
    n.count.assign(n.bins, 0.0);
    return n;
  }
  double width_;
  std::size_t reach_bins_;
  int dimension_;
  std::vector<CutNode> nodes_;
};

// The pieces of a tree's cut: the runs of one rank in storage order, a body
// kept whole in its first site's rank.
Decomposition pieces_of(const CaseSpec& spec, const BodyLayout& layout, const CutTree& tree,
                        int ranks) {
  const std::vector<bool> whole = bodies_kept_whole(spec, layout, ranks);
  std::vector<std::size_t> starts;
  std::vector<int> owners;
  for (const std::size_t b : layout.order) {
    int body_rank = -1;
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
      const int rank = body_rank >= 0 ? body_rank : tree.rank_of(at);
      if (whole[b] && k == 0) body_rank = rank;
      if (owners.empty() || owners.back() != rank) {
        starts.push_back(layout.range[b].begin + k);
        owners.push_back(rank);
      }
    });
  }
  starts.push_back(layout.total);
  return decomposition_in_pieces(std::move(starts), std::move(owners), ranks);
}
}  // namespace

CaseCut cut_case(const CaseSpec& spec, int ranks, CutChoice choice) {
  CaseCut out;
  out.decomposition = decompose_case(spec, ranks);
  out.kind = "slabs";
  if (ranks < 2) return out;
  const BodyLayout layout = body_layout(spec);
  if (layout.total == 0) return out;
  const double reach = bond_reach(spec);
  const Survey s = survey(spec, layout, out.decomposition);
  // One pass: the slabs' halo (each cut inside a body, a plane across the
  // axis its body's fill advances along, holds the body's sites within
  // reach of it) and the sites binned across the case's longest extent,
  // which both trees cut first.
  CutTree bands(spec, s.lo, s.hi, ranks);
  double slab_ghosts = 0;
  for (const std::size_t b : layout.order) {
    std::vector<double> planes;
    const int slow = s.slow_axis[b];
    for (std::size_t c = 0; c < s.cut_body.size(); ++c)
      if (s.cut_body[c] == b && slow >= 0)
        planes.push_back(s.cut_at[c][static_cast<std::size_t>(slow)]);
    visit_body_sites(spec, b, [&](std::size_t, const Point3& at) {
      bands.count(at);
      for (const double plane : planes)
        if (std::abs(coordinate(at, slow) - plane) <= reach) slab_ghosts += 1;
    });
  }
  CutTree blocks = bands;
  const int axis = bands.root().axis;
  // Bands: the root cut once per rank. Blocks: halved, then each part's
  // sites counted and halved again (a pass per level).
  const double band_ghosts = bands.cut(0, ranks);
  double block_ghosts = blocks.cut(0, 2);
  for (std::vector<std::size_t> open = blocks.open_nodes(); !open.empty();
       open = blocks.open_nodes()) {
    for (const std::size_t b : layout.order)
      visit_body_sites(spec, b, [&](std::size_t, const Point3& at) { blocks.count(at); });
    for (const std::size_t k : open) block_ghosts += blocks.cut(k, 2);
  }
  // Every estimate is reported, whichever cut is taken.
  out.slab_ghosts = slab_ghosts;
  out.band_ghosts = band_ghosts;
  out.block_ghosts = block_ghosts;
  CutChoice taken = choice;
  if (choice == CutChoice::automatic) {
    // A cut finer than slabs only where it saves a fifth of the halo.
    taken = CutChoice::slabs;
    double best = slab_ghosts;
    if (band_ghosts < 0.8 * best) taken = CutChoice::bands, best = band_ghosts;
    if (block_ghosts < 0.8 * best) taken = CutChoice::blocks;
  }
  if (taken == CutChoice::slabs) return out;
  const bool in_bands = taken == CutChoice::bands;
  out.decomposition = pieces_of(spec, layout, in_bands ? bands : blocks, ranks);
  out.kind = in_bands ? std::string("bands along ") + kAxisNames[axis] : std::string("blocks");
  return out;
}

}  // namespace mpsolid
