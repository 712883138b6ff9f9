#include "src/distributed/local_state.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

namespace mpsolid {

std::int64_t LocalLayout::find(std::size_t global) const {
  const auto at = std::lower_bound(global_of.begin(), global_of.end(), global);
  if (at == global_of.end() || *at != global) return -1;
  return at - global_of.begin();
}

std::size_t LocalLayout::local_of(std::uint32_t global) const {
  const std::int64_t at = find(global);
  if (at < 0) throw std::out_of_range("local_of: a particle this rank does not hold");
  return static_cast<std::size_t>(at);
}

LocalLayout local_layout(const Decomposition& d, const HaloPlan& halo, int rank,
                         const std::vector<std::uint32_t>& also) {
  LocalLayout layout;
  const Range mine = d.owned(rank);
  layout.owned_global = mine;
  std::vector<std::uint32_t> others;  // not owned: ghosts and `also`
  std::set_union(halo.ghosts.begin(), halo.ghosts.end(), also.begin(), also.end(),
                 std::back_inserter(others));
  std::erase_if(others, [&](std::uint32_t g) { return g >= mine.begin && g < mine.end; });
  const auto below = std::lower_bound(others.begin(), others.end(), mine.begin);
  layout.global_of.assign(others.begin(), below);
  layout.owned.begin = layout.global_of.size();
  for (std::size_t i = mine.begin; i < mine.end; ++i)
    layout.global_of.push_back(static_cast<std::uint32_t>(i));
  layout.owned.end = layout.global_of.size();
  layout.global_of.insert(layout.global_of.end(), below, others.end());
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
  p.set_kind_ranges();
  return p;
}

BondTable local_bonds(const BondTable& global, const ParticleStore& local,
                      const LocalLayout& layout) {
  std::vector<std::uint32_t> offsets(layout.size() + 1, 0), neighbor;
  const auto is_owned = [&](std::uint32_t g) {
    return g >= layout.owned_global.begin && g < layout.owned_global.end;
  };
  for (std::size_t k = 0; k < layout.size(); ++k) {
    const std::size_t g = layout.global_of[k];
    const bool whole = k >= layout.owned.begin && k < layout.owned.end;
    for (std::uint32_t b = global.begin(g); b < global.end(g); ++b) {
      const std::uint32_t j = global.neighbor[b];
      if (whole || is_owned(j)) neighbor.push_back(static_cast<std::uint32_t>(layout.local_of(j)));
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
  const Range mine = layout.owned_global;
  if (global.begin >= mine.begin && global.end <= mine.end) return Ownership::owned;
  if (global.end <= mine.begin || global.begin >= mine.end) return Ownership::elsewhere;
  return Ownership::split;
}
Range to_local(Range global, const LocalLayout& layout) {
  const std::size_t shift = layout.owned_global.begin - layout.owned.begin;
  return {global.begin - shift, global.end - shift};
}

// The items (rigid bodies, loads) whose particles this rank owns, in local
// indices; one whose particles are split between ranks is refused.
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
    kept.back().range = to_local(item.range, layout);
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
  s.rigid_bodies = owned_items(global.rigid_bodies, layout, "rigid body");
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
    const Range mine = layout.owned_global;
    const Range part{std::max(hold.range.begin, mine.begin), std::min(hold.range.end, mine.end)};
    if (part.begin < part.end) s.holds.push_back({to_local(part, layout), hold.x, hold.y, hold.z});
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
