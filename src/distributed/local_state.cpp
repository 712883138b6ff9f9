#include "src/distributed/local_state.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

namespace mpsolid {

void LocalLayout::set_owned_pieces(std::vector<Range> pieces) {
  owned_pieces = std::move(pieces);
  piece_local.clear();
  std::size_t at = owned.begin;
  for (const Range r : owned_pieces) {
    piece_local.push_back(at);
    at += r.size();
  }
  if (at != owned.end) throw std::logic_error("LocalLayout: the owned pieces do not fill it");
}

namespace {
// The owned piece at or before `global` (its index; pieces.size() when none).
std::size_t piece_at(const std::vector<Range>& pieces, std::size_t global) {
  const auto after = std::upper_bound(pieces.begin(), pieces.end(), global,
                                      [](std::size_t g, Range r) { return g < r.begin; });
  return after == pieces.begin() ? pieces.size()
                                 : static_cast<std::size_t>(after - pieces.begin()) - 1;
}
}  // namespace

bool LocalLayout::owns(std::size_t global) const {
  const std::size_t k = piece_at(owned_pieces, global);
  return k < owned_pieces.size() && global < owned_pieces[k].end;
}

std::size_t LocalLayout::local_of_owned(std::size_t global) const {
  const std::size_t k = piece_at(owned_pieces, global);
  return piece_local[k] + (global - owned_pieces[k].begin);
}

Range LocalLayout::owned_within(Range global) const {
  // The local index of the first owned particle at or after g.
  const auto first_at = [&](std::size_t g) {
    const std::size_t k = piece_at(owned_pieces, g);
    if (k == owned_pieces.size()) return owned.begin;
    const Range r = owned_pieces[k];
    return piece_local[k] + (std::min(g, r.end) - r.begin);
  };
  return {first_at(global.begin), first_at(global.end)};
}

Range LocalLayout::global_of_owned(Range local) const {
  const auto after = std::upper_bound(piece_local.begin(), piece_local.end(), local.begin);
  const std::size_t k =
      after == piece_local.begin() ? 0 : static_cast<std::size_t>(after - piece_local.begin()) - 1;
  const std::size_t shift = owned_pieces.at(k).begin - piece_local[k];
  return {local.begin + shift, local.end + shift};
}

std::int64_t LocalLayout::find(std::size_t global) const {
  // Each of the three parts is ascending.
  const auto in = [&](std::size_t from, std::size_t to) -> std::int64_t {
    const auto first = global_of.begin() + static_cast<long>(from);
    const auto last = global_of.begin() + static_cast<long>(to);
    const auto at = std::lower_bound(first, last, global);
    return at != last && *at == global ? at - global_of.begin() : -1;
  };
  if (owns(global)) return static_cast<std::int64_t>(local_of_owned(global));
  const std::int64_t below = in(0, owned.begin);
  return below >= 0 ? below : in(owned.end, global_of.size());
}

std::size_t LocalLayout::local_of(std::uint32_t global) const {
  const std::int64_t at = find(global);
  if (at < 0) throw std::out_of_range("local_of: a particle this rank does not hold");
  return static_cast<std::size_t>(at);
}

LocalLayout local_layout(const Decomposition& d, const HaloPlan& halo, int rank,
                         const std::vector<std::uint32_t>& also) {
  LocalLayout layout;
  const std::vector<Range> pieces = d.pieces(rank);
  std::vector<std::uint32_t> others;  // not owned: ghosts and `also`
  std::set_union(halo.ghosts.begin(), halo.ghosts.end(), also.begin(), also.end(),
                 std::back_inserter(others));
  std::erase_if(others, [&](std::uint32_t g) { return d.owner_of(g) == rank; });
  const std::size_t first = pieces.empty() ? d.particles() : pieces.front().begin;
  const auto below = std::lower_bound(others.begin(), others.end(), first);
  layout.global_of.assign(others.begin(), below);
  layout.owned.begin = layout.global_of.size();
  for (const Range r : pieces)
    for (std::size_t i = r.begin; i < r.end; ++i)
      layout.global_of.push_back(static_cast<std::uint32_t>(i));
  layout.owned.end = layout.global_of.size();
  layout.global_of.insert(layout.global_of.end(), below, others.end());
  layout.set_owned_pieces(pieces);
  return layout;
}

ParticleStore local_particles(const ParticleStore& global, const LocalLayout& layout) {
  ParticleStore p;
  p.dimension = global.dimension;
  p.resize(layout.size());
  for (std::size_t k = 0; k < layout.size(); ++k) {
    const std::size_t g = layout.global_of[k];
    for_each_particle_member([&](const auto& info, auto member) {
      if (info.present_in(p.dimension)) (p.*member)[k] = (global.*member)[g];
    });
  }
  // Kinds are grouped up to the owned particles' end (everything below is
  // in global order); in one slab the ghosts above follow on.
  if (layout.owned_pieces.size() > 1)
    p.set_kind_ranges(layout.owned.end);
  else
    p.set_kind_ranges();
  return p;
}

BondTable local_bonds(const BondTable& global, const ParticleStore& local,
                      const LocalLayout& layout) {
  std::vector<std::uint32_t> offsets(layout.size() + 1, 0), neighbor;
  for (std::size_t k = 0; k < layout.size(); ++k) {
    const std::size_t g = layout.global_of[k];
    const bool whole = k >= layout.owned.begin && k < layout.owned.end;
    for (std::uint32_t b = global.begin(g); b < global.end(g); ++b) {
      const std::uint32_t j = global.neighbor[b];
      if (whole || layout.owns(j))
        neighbor.push_back(static_cast<std::uint32_t>(layout.local_of(j)));
    }
    offsets[k + 1] = static_cast<std::uint32_t>(neighbor.size());
  }
  return make_bond_table(local, std::move(offsets), std::move(neighbor), global.geometry);
}

namespace {
// Where a global range lies for this rank: wholly owned (its local range),
// not held at all, or split (refused).
enum class Ownership { owned, elsewhere, split };
Ownership ownership(Range global, const LocalLayout& layout) {
  if (global.empty()) return layout.owns(global.begin) ? Ownership::owned : Ownership::elsewhere;
  const std::size_t held = layout.owned_within(global).size();
  if (held == global.size()) return Ownership::owned;
  return held == 0 ? Ownership::elsewhere : Ownership::split;
}

// The loads whose particles this rank owns, in local indices; one whose
// particles are split between ranks is refused.
template <class Item>
std::vector<Item> owned_items(const std::vector<Item>& items, const LocalLayout& layout,
                              const std::string& what) {
  std::vector<Item> kept;
  for (const Item& item : items) {
    const Ownership o = ownership(item.range, layout);
    if (o == Ownership::split)
      throw std::invalid_argument(what + " '" + item.name +
                                  "' is split between ranks: not supported yet (docs/mpi.md)");
    if (o == Ownership::elsewhere) continue;
    kept.push_back(item);
    kept.back().range = layout.owned_within(item.range);
  }
  return kept;
}
}  // namespace

SolverState local_solver_state(const SolverState& global, const LocalLayout& layout) {
  SolverState s;
  s.particles = local_particles(global.particles, layout);
  s.bonds = local_bonds(global.bonds, s.particles, layout);
  s.step = global.step;
  s.peak_work = global.peak_work;
  s.damping = global.damping;
  // A rigid body may be split: each rank its own particles of it.
  for (const RigidBody& body : global.rigid_bodies) {
    const Range mine = layout.owned_within(body.range);
    if (mine.empty()) continue;
    std::vector<std::size_t> places;
    for (std::size_t i = mine.begin; i < mine.end; ++i)
      places.push_back(layout.global_of[i] - body.range.begin);
    s.rigid_bodies.push_back(rigid_body_part(body, mine, places));
  }
  // A force on a body reads all its particles (its centroid): the body is
  // owned whole. A pressure may be split: every rank holds it (its running
  // step is the same on all), positioning the nodes it hosts.
  for (const StepLoad& load : global.loads) {
    if (!load.is_pressure()) {
      for (StepLoad& kept : owned_items(std::vector<StepLoad>{load}, layout, "the body of load"))
        s.loads.push_back(std::move(kept));
      continue;
    }
    StepLoad local = load;
    local.range = {};  // a pressure's work and forces go by its nodes
    local.surface = local_pressure_surface(
        load.surface,
        [&](std::uint32_t g) {
          const std::int64_t at = layout.find(g);
          return at >= 0 ? static_cast<std::uint32_t>(at) : PressureSurface::kElsewhere;
        },
        [&](std::uint32_t i) { return i >= layout.owned.begin && i < layout.owned.end; });
    s.loads.push_back(std::move(local));
  }
  for (const HeldRange& hold : global.holds) {
    const Range part = layout.owned_within(hold.range);
    if (!part.empty()) s.holds.push_back({part, hold.x, hold.y, hold.z});
  }
  // Every candidate of the run (the layout must hold them all); the list is
  // the decomposed step's to build.
  const ContactState& contact = global.contact;
  if (contact.enabled()) {
    ContactState& c = s.contact;
    c.parameters = contact.parameters;
    for (const std::uint32_t g : contact.candidates)
      c.candidates.push_back(static_cast<std::uint32_t>(layout.local_of(g)));
    c.group = contact.group;
    c.first_moving = contact.first_moving;
    c.zero_forces(s.particles.dimension);
  }
  return s;
}

}  // namespace mpsolid
