#include "src/solver/part_setup.hpp"

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <stdexcept>

#include "kernels/model_registry.hpp"
#include "neighbor/bond_search.hpp"
#include "src/core/ordered_sum.hpp"
#include "src/solver/contact_setup.hpp"
#include "src/solver/gas_outlines.hpp"
#include "src/solver/initial_motion.hpp"
#include "src/solver/setup.hpp"

namespace mpsolid {

namespace {
// How many particles of `r` the pieces `mine` (ascending) hold.
std::size_t held_of(Range r, const std::vector<Range>& mine) {
  std::size_t n = 0;
  for (const Range m : mine)
    if (std::max(r.begin, m.begin) < std::min(r.end, m.end))
      n += std::min(r.end, m.end) - std::max(r.begin, m.begin);
  return n;
}
bool overlaps(Range a, const std::vector<Range>& mine) {
  return held_of(a, mine) > 0;
}
bool inside(Range a, const std::vector<Range>& mine) {
  return held_of(a, mine) == a.size();
}
bool in_pieces(std::size_t g, const std::vector<Range>& mine) {
  const auto after = std::upper_bound(mine.begin(), mine.end(), g,
                                      [](std::size_t i, Range m) { return i < m.begin; });
  return after != mine.begin() && g < std::prev(after)->end;
}

// A site the part holds: its global storage index, body and place in the
// body's fill.
struct HeldSite {
  std::size_t global, body, k;
  Point3 at;
};

// The sites of the owned pieces `mine`, every site within `reach` of the
// box of the owned sites of one body and the sites `also` (global storage
// indices, ascending), in global storage order. A bond joins sites closer
// than the reach, so every partner of an owned site lies within reach of
// its body's box; one box per body keeps a small body that spans the case
// (a wall, a plate) from pulling in every site beside it.
std::vector<HeldSite> held_sites(const CaseSpec& spec, const BodyLayout& layout,
                                 const std::vector<Range>& mine, double reach,
                                 const std::vector<std::uint32_t>& also) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  struct Box {
    std::array<double, 3> lo{inf, inf, inf}, hi{-inf, -inf, -inf};
  };
  std::vector<Box> boxes;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const Range r = layout.range[b];
    if (!overlaps(r, mine)) continue;
    Box& box = boxes.emplace_back();
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
      const std::size_t g = r.begin + k;
      if (!in_pieces(g, mine)) return;
      const double c[3] = {at.x, at.y, at.z};
      for (int a = 0; a < 3; ++a) {
        box.lo[a] = std::min(box.lo[a], c[a]);
        box.hi[a] = std::max(box.hi[a], c[a]);
      }
    });
  }
  std::vector<HeldSite> out;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    const Range r = layout.range[b];
    visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
      const std::size_t g = r.begin + k;
      const double c[3] = {at.x, at.y, at.z};
      bool near = in_pieces(g, mine) || std::binary_search(also.begin(), also.end(), g);
      for (std::size_t n = 0; n < boxes.size() && !near; ++n) {
        near = true;
        for (int a = 0; a < 3; ++a)
          near = near && c[a] >= boxes[n].lo[a] - reach && c[a] <= boxes[n].hi[a] + reach;
      }
      if (near) out.push_back({g, b, k, at});
    });
  }
  std::sort(out.begin(), out.end(),
            [](const HeldSite& a, const HeldSite& b) { return a.global < b.global; });
  return out;
}

// Each elastic body's centroid of its sites, summed as centroid() sums its
// particles (ordered_sum's chunks from the body's first particle), for the
// bodies the part holds some of (`held`: each body's held range).
std::vector<std::array<double, 3>> centroids(const CaseSpec& spec, const BodyLayout& layout,
                                             const std::vector<Range>& held) {
  std::vector<std::array<double, 3>> out(spec.bodies.size(), {0.0, 0.0, 0.0});
  for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
    if (spec.bodies[b].kind != Kind::elastic || held[b].empty()) continue;
    std::array<double, 3> total{}, chunk{};
    std::size_t in_chunk = 0;
    const auto add_chunk = [&] {
      for (int a = 0; a < 3; ++a) total[a] += chunk[a];
      chunk = {};
      in_chunk = 0;
    };
    visit_body_sites(spec, b, [&](std::size_t, const Point3& at) {
      chunk[0] += at.x;
      chunk[1] += at.y;
      chunk[2] += at.z;
      if (++in_chunk == kSumChunk) add_chunk();
    });
    if (in_chunk > 0) add_chunk();
    const auto n = static_cast<double>(layout.range[b].size());
    out[b] = {total[0] / n, total[1] / n, spec.dimension == 3 ? total[2] / n : 0.0};
  }
  return out;
}

// Each probe's particle (global storage index): the nearest site to its
// point, the lowest id on a tie, as set_up finds it.
std::vector<std::size_t> probe_particles(const CaseSpec& spec, const BodyLayout& layout) {
  std::vector<std::size_t> out;
  for (const ProbeSpec& probe : spec.probes) {
    std::size_t best = 0, best_id = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < spec.bodies.size(); ++b)
      visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
        const double dx = at.x - probe.at[0], dy = at.y - probe.at[1];
        const double dz = spec.dimension == 3 ? at.z - probe.at[2] : 0.0;
        const double d2 = dx * dx + dy * dy + dz * dz;
        const std::size_t id = layout.first_id[b] + k;
        if (d2 < best_d2 || (d2 == best_d2 && id < best_id)) {
          best = layout.range[b].begin + k;
          best_id = id;
          best_d2 = d2;
        }
      });
    out.push_back(best);
  }
  return out;
}

// A rigid body made whole on the side, from all its sites: its make-up (and
// those of its particles), as set_up makes it.
struct WholeRigidBody {
  ParticleStore particles;
  RigidBody body;
};
WholeRigidBody whole_rigid_body(const CaseSpec& spec, const BodyLayout& layout, std::size_t b) {
  WholeRigidBody w;
  ParticleStore& whole = w.particles;
  whole.dimension = spec.dimension;
  whole.resize(layout.range[b].size());
  visit_body_sites(spec, b, [&](std::size_t k, const Point3& at) {
    place_particle(whole, k, spec, b, at, layout.first_id[b] + k);
  });
  whole.set_kind_ranges();
  w.body = make_rigid_body(whole, spec.bodies[b].name, whole.all());
  w.body.motion = spec.bodies[b].motion;
  return w;
}

// A rigid body another rank owns whose particles this part holds as ghosts:
// they move with it from the start (set_rigid_motion places them), so the
// body is made whole on the side, set moving, and its held particles copied.
void place_ghost_rigid_body(const CaseSpec& spec, const BodyLayout& layout, std::size_t b,
                            Range held, bool with_rotation, ParticleStore& p) {
  const BodySpec& body = spec.bodies[b];
  auto [whole, rigid] = whole_rigid_body(spec, layout, b);
  set_rigid_motion(whole, rigid, body.velocity, body.spin, with_rotation);
  for (std::size_t w = held.begin; w < held.end; ++w) {
    const auto k = static_cast<std::size_t>(p.id[w]) - layout.first_id[b];
    for_each_particle_member([&](const auto& info, auto member) {
      if (info.present_in(p.dimension)) (p.*member)[w] = (whole.*member)[k];
    });
  }
}

std::invalid_argument split(const std::string& what, const std::string& name) {
  return std::invalid_argument(what + " '" + name +
                               "' is split between ranks: not supported yet (docs/mpi.md)");
}
}  // namespace

double bond_reach(const CaseSpec& spec) {
  return case_bond_geometry(spec).re * (1.0 + 1e-9) + 1e-9 * spec.l0;
}

std::vector<bool> bodies_kept_whole(const CaseSpec& spec, const BodyLayout& layout, int ranks) {
  const double share = static_cast<double>(layout.total) / std::max(ranks, 1);
  std::vector<bool> whole(spec.bodies.size(), false);
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    whole[b] = spec.bodies[b].kind == Kind::rigid &&
               static_cast<double>(layout.range[b].size()) <= 0.1 * share;
  for (const LoadSpec& l : spec.loads)
    if (l.type != LoadSpec::Type::pressure) whole[static_cast<std::size_t>(l.body)] = true;
  return whole;
}

Decomposition decompose_case(const CaseSpec& spec, int ranks) {
  const BodyLayout layout = body_layout(spec);
  const std::vector<bool> kept = bodies_kept_whole(spec, layout, ranks);
  std::vector<Range> whole;
  for (const std::size_t b : layout.order)
    if (kept[b]) whole.push_back(layout.range[b]);
  return decompose_count(layout.total, ranks, whole);
}

namespace {
// The held sites as a state of their own, in global order ("window"
// indices), placed and bonded as set_up places and bonds the whole; each
// one's global storage index.
struct Window {
  SolverState state;
  std::vector<std::uint32_t> global_of;
  std::size_t index(std::size_t g) const {
    return static_cast<std::size_t>(std::lower_bound(global_of.begin(), global_of.end(), g) -
                                    global_of.begin());
  }
  Range range(Range r) const { return {index(r.begin), index(r.end)}; }
};
Window make_window(const CaseSpec& spec, const BodyLayout& layout, const BondGeometry& geometry,
                   const std::vector<HeldSite>& sites) {
  Window w;
  ParticleStore& p = w.state.particles;
  p.dimension = spec.dimension;
  p.resize(sites.size());
  w.global_of.resize(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const HeldSite& h = sites[i];
    place_particle(p, i, spec, h.body, h.at, layout.first_id[h.body] + h.k);
    w.global_of[i] = static_cast<std::uint32_t>(h.global);
  }
  p.set_kind_ranges();
  w.state.bonds = build_bonds(p, geometry);
  w.state.body_ranges.resize(spec.bodies.size());
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    w.state.body_ranges[b] = w.range(layout.range[b]);
  return w;
}

// Every contact candidate of the run (global storage indices, ascending)
// and its group: each rank finds those among its own sites, whose bond rows
// the window holds whole, piece by piece, and the ranks share them (in rank
// order, then put in storage order: a cut in pieces interleaves the ranks').
CandidateList every_candidate(const CaseSpec& spec, const Window& w, const std::vector<Range>& mine,
                              const RankGroup& world) {
  CandidateList own;
  for (const Range piece : mine) find_contact_candidates(spec, w.state, w.range(piece), own);
  std::vector<double> pairs;
  for (std::size_t k = 0; k < own.index.size(); ++k)
    pairs.insert(pairs.end(), {static_cast<double>(w.global_of[own.index[k]]),
                               static_cast<double>(own.group[k])});
  const std::vector<double> all = world.all_gather(pairs);
  std::vector<std::pair<std::uint32_t, std::int32_t>> found;
  for (std::size_t k = 0; k + 1 < all.size(); k += 2)
    found.emplace_back(static_cast<std::uint32_t>(all[k]), static_cast<std::int32_t>(all[k + 1]));
  std::sort(found.begin(), found.end());
  CandidateList every;
  for (const auto& [index, group] : found) {
    every.index.push_back(index);
    every.group.push_back(group);
  }
  return every;
}
}  // namespace

LocalPart set_up_part(const CaseSpec& spec, const Decomposition& d, int rank,
                      const RankGroup* world) {
  if (spec.contact.enabled && world == nullptr)
    throw std::logic_error("set_up_part: contact needs the ranks to share their candidates");
  const BodyLayout layout = body_layout(spec);
  const std::vector<Range> mine = d.pieces(rank);
  const BondGeometry geometry = case_bond_geometry(spec);
  // Every partner of an owned site lies within reach of the owned sites' box.
  const double reach = bond_reach(spec);
  Window window = make_window(spec, layout, geometry, held_sites(spec, layout, mine, reach, {}));
  if (spec.contact.enabled) {
    // Every candidate of the run among the part's particles (the decomposed
    // contact pass pairs them): those not held yet are added.
    CandidateList every = every_candidate(spec, window, mine, *world);
    if (!std::includes(window.global_of.begin(), window.global_of.end(), every.index.begin(),
                       every.index.end()))
      window =
          make_window(spec, layout, geometry, held_sites(spec, layout, mine, reach, every.index));
    for (std::uint32_t& g : every.index) g = static_cast<std::uint32_t>(window.index(g));
    window.state.contact = contact_over(spec, window.state.particles, std::move(every));
  }
  SolverState& s = window.state;
  ParticleStore& p = s.particles;
  const std::vector<std::uint32_t>& global_of = window.global_of;

  // The rigid bodies this rank owns particles of (set_up's order); one split
  // between ranks made whole on the side, its held particles kept.
  for (const std::size_t b : layout.order) {
    const BodySpec& body = spec.bodies[b];
    if (body.kind != Kind::rigid || !overlaps(layout.range[b], mine)) continue;
    if (inside(layout.range[b], mine)) {
      s.rigid_bodies.push_back(make_rigid_body(p, body.name, s.body_ranges[b]));
      s.rigid_bodies.back().motion = body.motion;
      continue;
    }
    const Range held = s.body_ranges[b];
    std::vector<std::size_t> places;
    for (std::size_t w = held.begin; w < held.end; ++w)
      places.push_back(static_cast<std::size_t>(p.id[w]) - layout.first_id[b]);
    s.rigid_bodies.push_back(rigid_body_part(whole_rigid_body(spec, layout, b).body, held, places));
  }
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].hold != Hold::none && !s.body_ranges[b].empty())
      s.holds.push_back(body_hold(spec.bodies[b], s.body_ranges[b]));
  // Every part holds every node of a pressure (local_solver_state): the
  // whole body's surface, over the sites the window holds.
  const auto over_window = [&](const PressureSurface& whole) {
    return local_pressure_surface(
        whole,
        [&](std::uint32_t g) {
          const std::size_t w = window.index(g);
          return w < global_of.size() && global_of[w] == g ? static_cast<std::uint32_t>(w)
                                                           : PressureSurface::kElsewhere;
        },
        [](std::uint32_t) { return false; });
  };
  // The loads of bodies this rank owns (their first steps wait for dt:
  // schedule_loads), then the gas's (set_up's order).
  for (const LoadSpec& l : spec.loads) {
    const auto b = static_cast<std::size_t>(l.body);
    if (l.type == LoadSpec::Type::pressure) {
      StepLoad load = body_load(l, s.body_ranges[b], p);
      load.surface = over_window(case_pressure_surface(spec, l, layout.range[b].begin));
      s.loads.push_back(std::move(load));
      continue;
    }
    if (!overlaps(layout.range[b], mine)) continue;
    if (!inside(layout.range[b], mine)) throw split("the body of load", l.name);
    s.loads.push_back(body_load(l, s.body_ranges[b], p));
  }
  for (StepLoad& load : gas_loads(spec, layout.range)) {
    load.surface = over_window(load.surface);
    load.range = window.range(load.range);
    s.loads.push_back(std::move(load));
  }
  const std::vector<std::array<double, 3>> centres = centroids(spec, layout, s.body_ranges);
  const bool with_rotation = model_info(spec.model).uses_rotation;
  apply_initial_motion(s, spec, with_rotation, &centres);
  // Those it holds only ghosts of (the part of a body it owns some of
  // placed every particle of it held here).
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].kind == Kind::rigid && !s.body_ranges[b].empty() &&
        !overlaps(layout.range[b], mine))
      place_ghost_rigid_body(spec, layout, b, s.body_ranges[b], with_rotation, p);

  // The part in window indices (the cut there: each rank's first held
  // particle), then in global ones.
  Decomposition window_cut = d;
  for (std::size_t& start : window_cut.starts) start = window.index(start);
  LocalPart part = local_part(s, window_cut, rank);
  part.decomposition = d;
  for (std::uint32_t& g : part.layout.global_of) g = global_of[g];
  part.layout.set_owned_pieces(mine);
  part.moving_begin = 0;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].kind == Kind::wall) part.moving_begin += layout.range[b].size();
  part.body_ranges = layout.range;
  part.probes = probe_particles(spec, layout);
  return part;
}

}  // namespace mpsolid
