#include "src/solver/gas_outlines.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "src/core/surface.hpp"

namespace mpsolid {

namespace {
bool moves(const CaseSpec& spec, int body) {
  return spec.bodies[static_cast<std::size_t>(body)].kind != Kind::wall;
}

PressureSurface gas_outline(const CaseSpec& spec, int body, std::size_t first) {
  const Shape& shape = spec.bodies[static_cast<std::size_t>(body)].shape;
  const Surface surface = build_surface(shape, fill_shape(shape, spec.l0), spec.l0);
  std::vector<std::uint32_t> all(surface.nodes());
  for (std::uint32_t k = 0; k < all.size(); ++k) all[k] = k;
  return make_pressure_surface(surface, all, first, 0.0, spec.depth);
}

// Body b's gas load among `loads`.
template <class Loads>
auto& gas_load_of(const CaseSpec& spec, int b, Loads& loads) {
  const std::string name = kGasLoadPrefix + spec.bodies[static_cast<std::size_t>(b)].name;
  const auto load =
      std::find_if(loads.begin(), loads.end(), [&](const StepLoad& l) { return l.name == name; });
  if (load == loads.end()) throw std::logic_error("no gas load " + name);
  return *load;
}

// Node k's position and velocity.
std::array<double, 4> node_motion(const ParticleStore& p, const PressureSurface& s, std::size_t k) {
  const Point2 x = affine_point(s.offsets, s.particle, s.weight, k, p.x.data(), p.y.data(), 0);
  const Point2 v = affine_point(s.offsets, s.particle, s.weight, k, p.vx.data(), p.vy.data(), 0);
  return {x.x, x.y, v.x, v.y};
}
}  // namespace

std::vector<PressureSurface> gas_outlines(const CaseSpec& spec,
                                          const std::vector<Range>& body_ranges) {
  std::vector<PressureSurface> out;
  for (const int b : spec.gas.bodies)
    out.push_back(gas_outline(spec, b, body_ranges.at(static_cast<std::size_t>(b)).begin));
  return out;
}

std::vector<PressureSurface> part_gas_outlines(const CaseSpec& spec,
                                               const std::vector<StepLoad>& loads,
                                               const std::vector<Range>& body_ranges,
                                               const LocalLayout& layout) {
  std::vector<PressureSurface> out;
  for (const int b : spec.gas.bodies) {
    // A moving body's outline is its gas load's surface, as the part holds it.
    if (moves(spec, b)) {
      out.push_back(gas_load_of(spec, b, loads).surface);
      continue;
    }
    out.push_back(local_pressure_surface(
        gas_outline(spec, b, body_ranges.at(static_cast<std::size_t>(b)).begin),
        [&](std::uint32_t g) {
          const std::int64_t at = layout.find(g);
          return at >= 0 ? static_cast<std::uint32_t>(at) : PressureSurface::kElsewhere;
        },
        [&](std::uint32_t i) { return i >= layout.owned.begin && i < layout.owned.end; }));
  }
  return out;
}

std::vector<StepLoad> gas_loads(const CaseSpec& spec, const std::vector<Range>& body_ranges) {
  std::vector<StepLoad> out;
  for (const int b : spec.gas.bodies) {
    if (!moves(spec, b)) continue;
    StepLoad& load = out.emplace_back();
    load.name = kGasLoadPrefix + spec.bodies[static_cast<std::size_t>(b)].name;
    load.range = body_ranges.at(static_cast<std::size_t>(b));
    load.surface = gas_outline(spec, b, load.range.begin);
    load.surface.given_fx.assign(load.surface.nodes(), 0.0);
    load.surface.given_fy.assign(load.surface.nodes(), 0.0);
  }
  return out;
}

OutlineMotion outline_motion(const ParticleStore& p, const std::vector<PressureSurface>& outlines) {
  OutlineMotion out;
  for (const PressureSurface& s : outlines) {
    std::vector<double>& nodes = out.emplace_back();
    nodes.reserve(4 * s.nodes());
    for (std::size_t k = 0; k < s.nodes(); ++k) {
      const std::array<double, 4> m = node_motion(p, s, k);
      nodes.insert(nodes.end(), m.begin(), m.end());
    }
  }
  return out;
}

void append_hosted_outline_motion(const ParticleStore& p,
                                  const std::vector<PressureSurface>& outlines,
                                  std::vector<double>& out) {
  for (std::size_t o = 0; o < outlines.size(); ++o)
    for (const std::uint32_t k : outlines[o].hosted) {
      const std::array<double, 4> m = node_motion(p, outlines[o], k);
      out.insert(out.end(),
                 {static_cast<double>(o), static_cast<double>(k), m[0], m[1], m[2], m[3]});
    }
}

OutlineMotion assemble_outline_motion(const std::vector<PressureSurface>& outlines,
                                      const std::vector<double>& hosted) {
  OutlineMotion out;
  std::vector<std::size_t> placed(outlines.size(), 0);
  for (const PressureSurface& s : outlines) out.emplace_back(4 * s.nodes(), 0.0);
  for (std::size_t at = 0; at + 6 <= hosted.size(); at += 6) {
    const auto o = static_cast<std::size_t>(hosted[at]);
    const auto k = static_cast<std::size_t>(hosted[at + 1]);
    std::copy_n(hosted.begin() + static_cast<long>(at + 2), 4,
                out.at(o).begin() + static_cast<long>(4 * k));
    ++placed.at(o);
  }
  for (std::size_t o = 0; o < outlines.size(); ++o)
    if (placed[o] != outlines[o].nodes())
      throw std::logic_error("assemble_outline_motion: not every node hosted once");
  return out;
}

OutlineMotion shared_outline_motion(RankPart& part, const std::vector<PressureSurface>& outlines,
                                    const RankGroup& world) {
  // A node's weights are its host's bond partners: the ghosts' positions
  // and velocities as they are now (a step's halos leave them a step
  // behind).
  ParticleStore& p = part.local.particles;
  exchange_halo(world, part.halo, "gas outlines",
                {field_of(p.x), field_of(p.y), field_of(p.vx), field_of(p.vy)}, part.halo_cost);
  std::vector<double> mine;
  append_hosted_outline_motion(p, outlines, mine);
  return assemble_outline_motion(outlines,
                                 gather_shared_values(world, mine, part.halo_cost, "gas outlines"));
}

void give_gas_forces(const CaseSpec& spec, std::vector<StepLoad>& loads,
                     const OutlineMotion& motion, const GasNodeForces& forces) {
  std::size_t at = 0;
  for (std::size_t o = 0; o < spec.gas.bodies.size(); ++o) {
    const int b = spec.gas.bodies[o];
    if (!moves(spec, b)) continue;
    StepLoad& load = gas_load_of(spec, b, loads);
    PressureSurface& s = load.surface;
    const std::size_t n = s.nodes();
    if (at + 2 * n > forces.size() || motion.at(o).size() != 4 * n)
      throw std::logic_error("give_gas_forces: the forces or the nodes do not fit " + load.name);
    std::vector<double> xyz(3 * n, 0.0);
    for (std::size_t k = 0; k < n; ++k) {
      xyz[3 * k] = motion[o][4 * k];
      xyz[3 * k + 1] = motion[o][4 * k + 1];
    }
    close_running_step_at(load, xyz);
    std::copy_n(forces.begin() + static_cast<long>(at), n, s.given_fx.begin());
    std::copy_n(forces.begin() + static_cast<long>(at + n), n, s.given_fy.begin());
    at += 2 * n;
    if (load.active) pressure_forces(load);
  }
  if (at != forces.size()) throw std::logic_error("give_gas_forces: forces left over");
}

}  // namespace mpsolid
