#include "src/case/resolved_case.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <toml.hpp>

#include "src/case/case_overrides.hpp"
#include "src/core/region3_boundary.hpp"
#include "src/core/region_boundary.hpp"

namespace mpsolid {

namespace {
std::string format_number(double x) {
  return fmt::format("{:.17g}", x);
}
std::string quote(const std::string& text) {
  return toml::format(TomlValue(text));
}
std::string key(const std::string& name) {
  return toml::format_key(name);
}

const char* hold_name(Hold hold) {
  return hold == Hold::x ? "x" : hold == Hold::y ? "y" : hold == Hold::z ? "z" : "none";
}

std::string pair(double a, double b) {
  return fmt::format("[{}, {}]", format_number(a), format_number(b));
}

// The first `count` numbers of v as a TOML array.
std::string numbers(const double* v, int count) {
  std::vector<std::string> items;
  for (int k = 0; k < count; ++k) items.push_back(format_number(v[k]));
  return fmt::format("[{}]", fmt::join(items, ", "));
}

std::string point3(Point3 p) {
  const double v[3] = {p.x, p.y, p.z};
  return numbers(v, 3);
}

bool any_nonzero(const double* v, int count) {
  return std::any_of(v, v + count, [](double x) { return x != 0; });
}

// A region's keys, "key = value" joined by `separator`.
std::string region_keys(const Region& region, const char* separator) {
  std::vector<std::string> keys;
  const std::string kind = region_kind(region);
  if (kind != "rectangle") keys.push_back(fmt::format("shape = \"{}\"", kind));
  if (const auto* r = std::get_if<RectangleRegion>(&region)) {
    keys.push_back("x = " + pair(r->x[0], r->x[1]));
    keys.push_back("y = " + pair(r->y[0], r->y[1]));
    if (r->angle_deg != 0) keys.push_back("angle = " + format_number(r->angle_deg));
  } else if (const auto* ci = std::get_if<CircleRegion>(&region)) {
    keys.push_back("center = " + pair(ci->center.x, ci->center.y));
    keys.push_back("radius = " + format_number(ci->radius));
  } else if (const auto* e = std::get_if<EllipseRegion>(&region)) {
    keys.push_back("center = " + pair(e->center.x, e->center.y));
    keys.push_back("semi_axes = " + pair(e->a, e->b));
    if (e->angle_deg != 0) keys.push_back("angle = " + format_number(e->angle_deg));
  } else if (const auto* a = std::get_if<AnnulusRegion>(&region)) {
    keys.push_back("center = " + pair(a->center.x, a->center.y));
    keys.push_back("radii = " + pair(a->inner, a->outer));
  } else if (const auto* p = std::get_if<PolygonRegion>(&region)) {
    // Inline, so the resolved case stands alone (a vertex file's too).
    std::vector<std::string> points;
    for (const Point2& v : p->vertices) points.push_back(pair(v.x, v.y));
    keys.push_back(fmt::format("vertices = [{}]", fmt::join(points, ", ")));
  }
  return fmt::format("{}", fmt::join(keys, separator));
}

// A load's history keys (none for a step), a table file's points inline.
std::string history_toml(const LoadHistory& h) {
  switch (h.kind) {
    case LoadHistory::Kind::step:
      return "";
    case LoadHistory::Kind::ramp:
      return fmt::format("history = \"ramp\"\nrise_time = {}\n", format_number(h.rise_time));
    case LoadHistory::Kind::table: {
      std::vector<std::string> points;
      for (std::size_t k = 0; k < h.times.size(); ++k)
        points.push_back(pair(h.times[k], h.factors[k]));
      return fmt::format("history = \"table\"\ntable = [{}]\n", fmt::join(points, ", "));
    }
    case LoadHistory::Kind::friedlander:
      return fmt::format("history = \"friedlander\"\nduration = {}\ndecay = {}\n",
                         format_number(h.duration), format_number(h.decay));
  }
  return "";
}

std::string shape_toml(const Shape& shape) {
  std::string out = region_keys(shape.region, "\n") + "\n";
  if (shape.holes.empty()) return out;
  std::vector<std::string> holes;
  for (const Region& hole : shape.holes) holes.push_back("{ " + region_keys(hole, ", ") + " }");
  return out + fmt::format("holes = [\n  {},\n]\n", fmt::join(holes, ",\n  "));
}

// A region of space's keys, as region_keys.
std::string region3_keys(const Region3& region, const char* separator) {
  std::vector<std::string> keys;
  const std::string kind = region3_kind(region);
  if (kind != "box") keys.push_back(fmt::format("shape = \"{}\"", kind));
  if (const auto* b = std::get_if<BoxRegion>(&region)) {
    keys.push_back("x = " + pair(b->x[0], b->x[1]));
    keys.push_back("y = " + pair(b->y[0], b->y[1]));
    keys.push_back("z = " + pair(b->z[0], b->z[1]));
  } else if (const auto* c = std::get_if<CylinderRegion>(&region)) {
    keys.push_back("base = " + point3(c->base));
    keys.push_back("top = " + point3(c->top));
    keys.push_back("radius = " + format_number(c->radius));
  } else if (const auto* sphere = std::get_if<SphereRegion>(&region)) {
    keys.push_back("center = " + point3(sphere->center));
    keys.push_back("radius = " + format_number(sphere->radius));
  } else if (const auto* e = std::get_if<ExtrusionRegion>(&region)) {
    std::string section = region_keys(e->section.region, ", ");
    if (!e->section.holes.empty()) {
      std::vector<std::string> holes;
      for (const Region& hole : e->section.holes)
        holes.push_back("{ " + region_keys(hole, ", ") + " }");
      section += fmt::format(", holes = [{}]", fmt::join(holes, ", "));
    }
    keys.push_back("section = { " + section + " }");
    keys.push_back("z = " + pair(e->z[0], e->z[1]));
  }
  return fmt::format("{}", fmt::join(keys, separator));
}

std::string shape3_toml(const Shape3& shape) {
  std::string out = region3_keys(shape.region, "\n") + "\n";
  if (shape.holes.empty()) return out;
  std::vector<std::string> holes;
  for (const Region3& hole : shape.holes) holes.push_back("{ " + region3_keys(hole, ", ") + " }");
  return out + fmt::format("holes = [\n  {},\n]\n", fmt::join(holes, ",\n  "));
}

std::string gas_state_toml(const GasStateSpec& s) {
  return fmt::format("density = {}\npressure = {}\nvelocity = {}\n", format_number(s.density),
                     format_number(s.pressure), pair(s.velocity[0], s.velocity[1]));
}

const char* edge_name(GasSpec::Edge e) {
  return e == GasSpec::Edge::inflow    ? "inflow"
         : e == GasSpec::Edge::outflow ? "outflow"
                                       : "slip_wall";
}

std::string gas_toml(const CaseSpec& c) {
  const GasSpec& g = c.gas;
  if (!g.enabled) return "";
  std::vector<std::string> bodies;
  for (const int b : g.bodies) bodies.push_back(quote(c.bodies[static_cast<std::size_t>(b)].name));
  std::string out = fmt::format(
      "\n[gas]\ngamma = {}\ncell = {}\nx = {}\ny = {}\ncfl = {}\nleft = \"{}\"\nright = "
      "\"{}\"\nbottom = \"{}\"\ntop = \"{}\"\nreference_pressure = {}\nbodies = [{}]\n",
      format_number(g.gamma), format_number(g.cell), pair(g.x[0], g.x[1]), pair(g.y[0], g.y[1]),
      format_number(g.cfl), edge_name(g.edges[0][0]), edge_name(g.edges[0][1]),
      edge_name(g.edges[1][0]), edge_name(g.edges[1][1]), format_number(g.reference_pressure),
      fmt::join(bodies, ", "));
  out += "\n[gas.initial]\n" + gas_state_toml(g.initial);
  for (const GasSpec::Region& r : g.regions)
    out += fmt::format("\n[gas.regions.{}]\n", key(r.name)) + shape_toml(r.shape) +
           gas_state_toml(r.state);
  if (g.mach > 0)
    out +=
        fmt::format("\n[gas.shock]\nmach = {}\nx = {}\ndirection = \"{}\"\n", format_number(g.mach),
                    format_number(g.shock_x), g.direction > 0 ? "+x" : "-x");
  if (g.inflow_given) out += "\n[gas.inflow]\n" + gas_state_toml(g.inflow);
  for (const GasSpec::Probe& p : g.probes)
    out += fmt::format("\n[gas.probes.{}]\nat = {}\n", key(p.name), pair(p.at[0], p.at[1]));
  return out;
}

std::string body_toml(const CaseSpec& c, const BodySpec& b) {
  std::string out =
      fmt::format("\n[bodies.{}]\nkind = \"{}\"\nmaterial = {}\n{}", key(b.name), kind_name(b.kind),
                  quote(c.materials[static_cast<std::size_t>(b.material)].name),
                  c.dimension == 3 ? shape3_toml(b.shape3) : shape_toml(b.shape));
  // Initial motion and holds only where set: walls accept none of them.
  if (any_nonzero(b.velocity, c.dimension))
    out += fmt::format("velocity = {}\n", numbers(b.velocity, c.dimension));
  if (c.dimension == 3 && any_nonzero(b.spin, 3))
    out += fmt::format("spin = {}\n", numbers(b.spin, 3));
  if (c.dimension == 2 && b.spin[2] != 0)
    out += fmt::format("spin = {}\n", format_number(b.spin[2]));
  if (b.hold != Hold::none) out += fmt::format("hold = \"{}\"\n", hold_name(b.hold));
  if (b.motion.on)
    out += fmt::format("\n[bodies.{}.motion]\nvelocity = {}\nspin = {}\nstart = {}\n", key(b.name),
                       numbers(b.motion.velocity.data(), c.dimension),
                       c.dimension == 3 ? numbers(b.motion.spin.data(), 3)
                                        : format_number(b.motion.spin[2]),
                       format_number(b.motion.start)) +
           history_toml(b.motion.history);
  if (b.has_mode)
    out += fmt::format(
        "\n[bodies.{}.bending_mode]\nroot_x = {}\nlength = {}\nkL = {}\ntip_velocity = {}\n",
        key(b.name), format_number(b.mode.root_x), format_number(b.mode.length),
        format_number(b.mode.kl), format_number(b.mode.tip_velocity));
  return out;
}

const char* load_type(LoadSpec::Type type) {
  return type == LoadSpec::Type::step           ? "step"
         : type == LoadSpec::Type::acceleration ? "acceleration"
                                                : "pressure";
}

std::string selection_toml(const SurfaceSelection& s, const BodySpec& body, int dimension) {
  switch (s.kind) {
    case SurfaceSelection::Kind::all:
      return "";
    case SurfaceSelection::Kind::face:
      if (dimension == 3)
        return fmt::format(
            "face = {}\n",
            quote(region3_face_names(body.shape3.region)[static_cast<std::size_t>(s.face)]));
      if (std::holds_alternative<RectangleRegion>(body.shape.region))
        return fmt::format("face = \"{}\"\n", kRectangleFaces[s.face]);
      return fmt::format("face = {}\n", s.face + 1);
    case SurfaceSelection::Kind::box:
      if (dimension == 3)
        return fmt::format("box = {{ x = {}, y = {}, z = {} }}\n", pair(s.box.lo.x, s.box.hi.x),
                           pair(s.box.lo.y, s.box.hi.y), pair(s.box.lo.z, s.box.hi.z));
      return fmt::format("box = {{ x = {}, y = {} }}\n", pair(s.box.lo.x, s.box.hi.x),
                         pair(s.box.lo.y, s.box.hi.y));
    case SurfaceSelection::Kind::half_plane: {
      const double point[3] = {s.point.x, s.point.y, s.point.z};
      const double normal[3] = {s.normal.x, s.normal.y, s.normal.z};
      return fmt::format("{} = {{ point = {}, normal = {} }}\n",
                         dimension == 3 ? "half_space" : "half_plane", numbers(point, dimension),
                         numbers(normal, dimension));
    }
  }
  return "";
}

std::string time_toml(const CaseSpec& c) {
  if (c.dt_auto && c.dt == 0)
    return fmt::format("\n[time]\ndt = \"auto\"\nsafety = {}\nend = {}\n",
                       format_number(c.dt_safety), format_number(c.end));
  return fmt::format("\n[time]\ndt = {}\nend = {}\n", format_number(c.dt), format_number(c.end));
}

// The chosen model's options section, every key written.
std::string model_section_toml(const CaseSpec& c) {
  if (c.model_section.empty()) return "";
  std::string out = fmt::format("\n[{}]\n", key(c.model_section));
  for (const auto& [name, value] : c.model_options.numbers)
    out += fmt::format("{} = {}\n", key(name), format_number(value));
  for (const auto& [name, value] : c.model_options.choices)
    out += fmt::format("{} = {}\n", key(name), quote(value));
  return out;
}
}  // namespace

// Derived figures go in as comments.
std::string resolved_case_toml(const CaseSpec& c) {
  std::string out = fmt::format(
      "# Resolved by mpsolid from {}.\n# Derived: re = {} m, particle volume V = {} m^3\n",
      c.source, format_number(2.1 * c.l0), format_number(c.particle_volume()));
  for (const auto& m : c.materials)
    out += fmt::format("# material {}: lambda = {} Pa, mu = {} Pa\n", key(m.name),
                       format_number(m.lambda()), format_number(m.mu()));
  if (c.dimension == 3)
    out += fmt::format("\nname = {}\nmodel = {}\ndimension = 3\nl0 = {}\n", quote(c.name),
                       quote(c.model), format_number(c.l0));
  else
    out += fmt::format("\nname = {}\nmodel = {}\nl0 = {}\ndepth = {}\n", quote(c.name),
                       quote(c.model), format_number(c.l0), format_number(c.depth));
  for (const auto& m : c.materials)
    out += fmt::format("\n[materials.{}]\nE = {}\nnu = {}\nrho = {}\n", key(m.name),
                       format_number(m.youngs_modulus), format_number(m.poisson_ratio),
                       format_number(m.density));
  for (const auto& b : c.bodies) out += body_toml(c, b);
  for (const auto& l : c.loads) {
    const BodySpec& body = c.bodies[static_cast<std::size_t>(l.body)];
    out += fmt::format("\n[loads.{}]\ntype = \"{}\"\nbody = {}\n", key(l.name), load_type(l.type),
                       quote(body.name));
    if (l.type == LoadSpec::Type::step)
      out += fmt::format("force = {}\n", numbers(l.force, c.dimension));
    else if (l.type == LoadSpec::Type::acceleration)
      out += fmt::format("acceleration = {}\n", numbers(l.acceleration, c.dimension));
    else
      out += fmt::format("pressure = {}\n", format_number(l.pressure)) +
             selection_toml(l.surface, body, c.dimension);
    out += fmt::format("start = {}\n", format_number(l.start));
    out += history_toml(l.history);
  }
  if (c.damping.coefficient > 0)
    out += fmt::format("\n[damping]\ncoefficient = {}\nstart = {}\nend = {}\n",
                       format_number(c.damping.coefficient), format_number(c.damping.start),
                       format_number(c.damping.end));
  for (const auto& probe : c.probes)
    out += fmt::format("\n[probes.{}]\nat = {}\n", key(probe.name), numbers(probe.at, c.dimension));
  out += time_toml(c);
  out += fmt::format("\n[output]\nframe_interval = {}\nhistory_interval = {}\n",
                     format_number(c.frame_interval), format_number(c.history_interval));
  out += fmt::format("checkpoint_interval = {}\ncompression = {}\n",
                     format_number(c.checkpoint_interval), c.compression);
  out += model_section_toml(c);
  out += fmt::format(
      "\n[stability]\ncheck_interval = {}\nmax_speed = {}\nmin_jacobian = {}\nenergy_tolerance = "
      "{}\n",
      c.stability.check_interval, format_number(c.stability.max_speed),
      format_number(c.stability.min_jacobian), format_number(c.stability.energy_tolerance));
  if (c.contact.enabled) {
    std::vector<std::string> names;
    for (const int b : c.contact.bodies)
      names.push_back(quote(c.bodies[static_cast<std::size_t>(b)].name));
    out += fmt::format(
        "\n[contact]\nenabled = true\ndistance = {}\nskin = {}\nstiffness = {}\nmin_distance = "
        "{}\nbodies = [{}]\n",
        format_number(c.contact.distance), format_number(c.contact.skin),
        format_number(c.contact.stiffness), format_number(c.contact.min_distance),
        fmt::join(names, ", "));
  }
  out += gas_toml(c);
  out += fmt::format("\n[numerics]\nflush_subnormals = {}\n", c.flush_subnormals);
  return out;
}

}  // namespace mpsolid
