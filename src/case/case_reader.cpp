#include "src/case/case_reader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "src/case/case_overrides.hpp"
#include "src/case/gas_reader.hpp"
#include "src/case/history_reader.hpp"
#include "src/case/resolved_case.hpp"
#include "src/case/selection_reader.hpp"
#include "src/case/shape_reader.hpp"
#include "src/case/table_reader.hpp"

namespace mpsolid {

namespace {

// Bond indices and row offsets are 32-bit: up to 12 (and a few spare)
// entries per particle in the plane, 32 (and a few spare) in space.
double max_particles(int dimension) {
  return static_cast<double>(std::numeric_limits<std::uint32_t>::max() /
                             (dimension == 3 ? 40 : 16));
}

Kind parse_kind(TableReader& r, const std::string& key, const std::string& text) {
  if (text == "elastic") return Kind::elastic;
  if (text == "rigid") return Kind::rigid;
  if (text == "wall") return Kind::wall;
  r.fail(key, fmt::format("unknown kind '{}' (allowed: elastic, rigid, wall)", text));
}

Hold parse_hold(TableReader& r, const std::string& key, const std::string& text, int dimension) {
  if (text == "none") return Hold::none;
  if (text == "x") return Hold::x;
  if (text == "y") return Hold::y;
  if (text == "z" && dimension == 3) return Hold::z;
  r.fail(key, fmt::format("unknown hold '{}' (allowed: none, x, y{})", text,
                          dimension == 3 ? ", z" : ""));
}

// "[x, y]" or "[x, y, z]": the case's axes, for messages.
std::string axes_text(int dimension, const char* prefix = "") {
  return dimension == 3 ? fmt::format("[{0}x, {0}y, {0}z]", prefix)
                        : fmt::format("[{0}x, {0}y]", prefix);
}

// Calls each(name, value, reader) for every [SECTION.NAME] entry, in name
// order, then refuses the keys each() did not ask for; an entry that is not
// a table is refused with what it should hold.
template <class Each>
void for_each_named_table(const TomlValue& section, const std::string& section_name,
                          const std::string& file, const char* holds, Each&& each) {
  for (const auto& [name, value] : section.as_table()) {
    if (!value.is_table())
      throw InputError(fmt::format("{}: {}.{}: expected a table with {}", origin(value, file),
                                   section_name, name, holds));
    TableReader r(value, section_name + "." + name, file);
    each(name, value, r);
    r.finish();
  }
}

// A body's region as a case names it ("rectangle", "box", ...).
const char* body_kind_text(const BodySpec& b, int dimension) {
  return dimension == 3 ? region3_kind(b.shape3.region) : region_kind(b.shape.region);
}

Box3 flat_box(const Box2& b) {
  return {{b.lo.x, b.lo.y, 0}, {b.hi.x, b.hi.y, 0}};
}

std::vector<std::string> names_of(const auto& items) {
  std::vector<std::string> names;
  for (const auto& item : items) names.push_back(item.name);
  return names;
}

// The index of the item called by the string at `key` (a material, a body),
// or a refusal naming the ones defined.
template <class Items>
int index_by_name(TableReader& r, const std::string& key, const std::string& what,
                  const Items& items) {
  const std::string name = r.string(key, what);
  const auto it =
      std::find_if(items.begin(), items.end(), [&](const auto& item) { return item.name == name; });
  if (it == items.end())
    r.fail(key, fmt::format("no {} named '{}' (defined: {})", key, name, join(names_of(items))));
  return static_cast<int>(it - items.begin());
}

void read_model(TableReader& top, const std::vector<ModelInfo>& models, CaseSpec& c) {
  c.model = top.string_or("model", "paper");
  const auto it = std::find_if(models.begin(), models.end(),
                               [&](const ModelInfo& m) { return m.name == c.model; });
  if (it == models.end())
    top.fail("model",
             fmt::format("unknown model '{}' (allowed: {})", c.model, join(names_of(models))));
  c.model_section = it->section;
  c.model_options = default_options(it->options);
}

void read_materials(TableReader& top, CaseSpec& c) {
  const TomlValue& table = top.subtable("materials", "one [materials.NAME] table per material");
  if (table.as_table().empty())
    throw InputError(fmt::format("{}: materials: at least one material is needed", top.file()));
  for_each_named_table(table, "materials", top.file(), "E, nu, rho",
                       [&](const std::string& name, const TomlValue&, TableReader& r) {
                         Material m;
                         m.name = name;
                         m.youngs_modulus = r.number("E", "Young's modulus in Pa");
                         r.range_check("E", m.youngs_modulus, m.youngs_modulus > 0, "(0, inf) Pa");
                         m.poisson_ratio = r.number("nu", "Poisson's ratio");
                         r.range_check("nu", m.poisson_ratio,
                                       m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5,
                                       "(-1, 0.5)");
                         m.density = r.number("rho", "density in kg/m^3");
                         r.range_check("rho", m.density, m.density > 0, "(0, inf) kg/m^3");
                         c.materials.push_back(m);
                       });
}

// velocity, spin, hold and bending_mode of a [bodies.NAME] table.
// [bodies.NAME.motion]: velocity = [vx, vy] (in space [vx, vy, vz]), spin
// (in space the vector [wx, wy, wz]), start and a history. A wall driven so
// is stepped as a rigid body: both follow the motion alone.
void read_prescribed_motion(TableReader& r, BodySpec& b, const std::string& case_file,
                            int dimension) {
  const TomlValue* table = r.subtable_or_null("motion");
  if (!table) return;
  if (b.kind == Kind::elastic)
    r.fail("motion", "only a wall or a rigid body can be driven (an elastic body takes loads)");
  for (const char* k : {"velocity", "spin"})
    if (r.has(k))
      r.fail(k, "a driven body moves as its motion says: give its velocity in motion.velocity");
  TableReader m(*table, r.key_path("motion"), r.file());
  PrescribedMotion& motion = b.motion;
  motion.on = true;
  m.numbers("velocity",
            "the velocity " + axes_text(dimension, "v") + " in m/s at a history factor of 1",
            motion.velocity.data(), dimension);
  if (dimension == 3)
    m.numbers_or("spin", "the angular velocity [wx, wy, wz] in rad/s at a history factor of 1",
                 motion.spin.data(), 3);
  else
    motion.spin[2] = m.number_or("spin", 0.0);
  motion.start = m.number_or("start", 0.0);
  m.range_check("start", motion.start, motion.start >= 0, "[0, inf) s");
  motion.history = read_history(m, case_file);
  m.finish();
  b.kind = Kind::rigid;
}

void read_body_motion(TableReader& r, BodySpec& b, int dimension) {
  const bool wall = b.kind == Kind::wall;
  for (const char* k : {"velocity", "spin", "hold", "bending_mode"})
    if (r.has(k) && wall) r.fail(k, "walls never move: a wall takes no initial motion or hold");
  r.numbers_or("velocity", "the initial velocity " + axes_text(dimension, "v") + " in m/s",
               b.velocity, dimension);
  if (dimension == 3)
    r.numbers_or("spin", "the angular velocity [wx, wy, wz] in rad/s", b.spin, 3);
  else
    b.spin[2] = r.number_or("spin", 0.0);
  b.hold = parse_hold(r, "hold", r.string_or("hold", "none"), dimension);
  if (b.kind == Kind::rigid && b.hold != Hold::none)
    r.fail("hold", "a rigid body cannot be held (use a wall for a fixed body, or a motion)");
  if (const TomlValue* table = r.subtable_or_null("bending_mode")) {
    if (b.kind != Kind::elastic)
      r.fail("bending_mode", "only an elastic body can start in a bending mode");
    TableReader m(*table, r.key_path("bending_mode"), r.file());
    b.has_mode = true;
    b.mode.root_x = m.number("root_x", "the x of the clamped end in m");
    b.mode.length = m.number("length", "the beam length L in m");
    m.range_check("length", b.mode.length, b.mode.length > 0, "(0, inf) m");
    b.mode.kl = m.number_or("kL", b.mode.kl);
    m.range_check("kL", b.mode.kl, b.mode.kl > 0 && b.mode.kl < 20, "(0, 20)");
    b.mode.tip_velocity = m.number("tip_velocity", "v_y at the free end in m/s");
    m.finish();
  }
}

void read_bodies(TableReader& top, CaseSpec& c) {
  const std::string& file = top.file();
  const TomlValue& table = top.subtable("bodies", "one [bodies.NAME] table per body");
  if (table.as_table().empty())
    throw InputError(fmt::format("{}: bodies: at least one body is needed", file));
  std::int64_t particle_total = 0;
  for_each_named_table(
      table, "bodies", file, "kind, material and a shape (x, y for a rectangle)",
      [&](const std::string& name, const TomlValue& value, TableReader& r) {
        BodySpec b;
        b.name = name;
        b.kind = parse_kind(r, "kind", r.string("kind", "elastic, rigid or wall"));
        b.material =
            index_by_name(r, "material", "the name of a [materials.NAME] table", c.materials);
        const bool space = c.dimension == 3;
        if (space) {
          b.shape3 = read_shape3(r, file);
        } else {
          b.shape = read_shape(r, file);
        }
        read_prescribed_motion(r, b, file, c.dimension);
        read_body_motion(r, b, c.dimension);
        // Estimate in floating point first: integer lattice indices would
        // overflow for an absurdly small l0.
        const Box3 box = space ? b.shape3.bounds() : flat_box(b.shape.bounds());
        double estimate =
            ((box.hi.x - box.lo.x) / c.l0 + 1.0) * ((box.hi.y - box.lo.y) / c.l0 + 1.0);
        if (space) estimate *= (box.hi.z - box.lo.z) / c.l0 + 1.0;
        if (!(estimate < max_particles(c.dimension)))
          top.fail("l0", fmt::format("l0 = {} m gives about {:.3g} particles in bodies.{}, more "
                                     "than this build supports ({} particles)",
                                     c.l0, estimate, name, max_particles(c.dimension)));
        const std::int64_t sites = b.site_count(c.l0, c.dimension);
        if (sites == 0)
          throw InputError(fmt::format(
              "{}: bodies.{}: the body is empty: no lattice site (centre at (k + 1/2) l0, l0 = "
              "{} m) lies in its {} (bounding box x = [{}, {}], y = [{}, {}]{}); make it larger "
              "or l0 smaller",
              origin(value, file), name, c.l0, body_kind_text(b, c.dimension), box.lo.x, box.hi.x,
              box.lo.y, box.hi.y,
              space ? fmt::format(", z = [{}, {}]", box.lo.z, box.hi.z) : std::string()));
        particle_total += sites;
        c.bodies.push_back(b);
      });
  for (std::size_t a = 0; a < c.bodies.size(); ++a)
    for (std::size_t b = a + 1; b < c.bodies.size(); ++b) {
      const BodySpec &first = c.bodies[a], &second = c.bodies[b];
      const bool overlap = c.dimension == 3 ? shapes3_share_site(first.shape3, second.shape3, c.l0)
                                            : shapes_overlap(first.shape, second.shape);
      if (overlap)
        throw InputError(fmt::format(
            "{}: bodies.{} ({}) and bodies.{} ({}) overlap; bodies may touch but not overlap", file,
            first.name, body_kind_text(first, c.dimension), second.name,
            body_kind_text(second, c.dimension)));
    }
  if (static_cast<double>(particle_total) >= max_particles(c.dimension))
    top.fail("l0", fmt::format("l0 = {} m gives {} particles, more than this build supports ({} "
                               "particles)",
                               c.l0, particle_total, max_particles(c.dimension)));
}

void read_damping(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("damping");
  if (!table) return;
  TableReader r(*table, "damping", top.file());
  DampingSpec& d = c.damping;
  d.coefficient = r.number("coefficient", "c in 1/s: the force -c m v on every moving particle");
  r.range_check("coefficient", d.coefficient, d.coefficient > 0, "(0, inf) 1/s");
  d.start = r.number_or("start", 0.0);
  r.range_check("start", d.start, d.start >= 0, "[0, inf) s");
  d.end = r.number("end", "when the damping stops, in s");
  r.range_check("end", d.end, d.end > d.start, fmt::format("({}, inf) s: after start", d.start));
  r.finish();
}

void read_loads(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("loads");
  if (!table) return;
  for_each_named_table(
      *table, "loads", top.file(), "type, body, force, acceleration or pressure, start",
      [&](const std::string& name, const TomlValue&, TableReader& r) {
        LoadSpec l;
        l.name = name;
        const std::string type = r.string_or("type", "step");
        if (type != "step" && type != "acceleration" && type != "pressure")
          r.fail(
              "type",
              fmt::format("unknown load type '{}' (allowed: step, acceleration, pressure)", type));
        l.type = type == "step"           ? LoadSpec::Type::step
                 : type == "acceleration" ? LoadSpec::Type::acceleration
                                          : LoadSpec::Type::pressure;
        l.body = index_by_name(r, "body", "the name of a [bodies.NAME] table", c.bodies);
        const BodySpec& body = c.bodies[static_cast<std::size_t>(l.body)];
        if (body.kind == Kind::wall)
          r.fail("body",
                 fmt::format("'{}' is a wall; walls do not move, so a load on it does nothing",
                             body.name));
        if (l.type == LoadSpec::Type::step) {
          r.numbers("force",
                    c.dimension == 3 ? "the total force [Fx, Fy, Fz] in N"
                                     : "the total force [Fx, Fy] in N (over the depth)",
                    l.force, c.dimension);
        } else if (l.type == LoadSpec::Type::pressure) {
          l.pressure = r.number("pressure", "the pressure in Pa (positive pushes inwards)");
          r.range_check("pressure", l.pressure, std::isfinite(l.pressure), "a finite number of Pa");
          l.surface = read_selection(r, body, c.l0, c.dimension);
        } else {
          r.numbers(
              "acceleration",
              "the acceleration " + axes_text(c.dimension, "a") + " in m/s^2 of every particle",
              l.acceleration, c.dimension);
        }
        l.start = r.number_or("start", 0.0);
        r.range_check("start", l.start, l.start >= 0, "[0, inf) s");
        l.history = read_history(r, top.file());
        c.loads.push_back(l);
      });
}

void read_probes(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("probes");
  if (!table) return;
  for_each_named_table(
      *table, "probes", top.file(), c.dimension == 3 ? "at = [x, y, z]" : "at = [x, y]",
      [&](const std::string& name, const TomlValue&, TableReader& r) {
        ProbeSpec probe;
        probe.name = name;
        r.numbers("at",
                  "the initial point " + axes_text(c.dimension) +
                      " in m whose nearest particle is followed",
                  probe.at, c.dimension);
        // A point off every body is a typo, not a request to follow a far
        // particle: some body's site must lie within 1.5 l0 of it.
        const double reach = 1.5 * c.l0;
        const bool on_a_body =
            std::any_of(c.bodies.begin(), c.bodies.end(), [&](const BodySpec& b) {
              return c.dimension == 3
                         ? shape3_has_site_near(b.shape3, {probe.at[0], probe.at[1], probe.at[2]},
                                                c.l0, reach)
                         : shape_has_site_near(b.shape, {probe.at[0], probe.at[1]}, c.l0, reach);
            });
        if (!on_a_body)
          r.fail("at", fmt::format("[{}] is not within l0 = {} m of any body (no particle "
                                   "within 1.5 l0)",
                                   fmt::join(probe.at, probe.at + c.dimension, ", "), c.l0));
        c.probes.push_back(probe);
      });
}

// With dt = "auto" the step is not known yet: intervals are checked against 0
// here, and whole-step cadences are kept at >= 1 step.
void read_time(TableReader& top, CaseSpec& c) {
  TableReader r(top.subtable("time", "[time] with dt and end"), "time", top.file());
  const TomlValue& dt = r.require("dt", "the time step in s, or \"auto\"");
  if (dt.is_string()) {
    if (dt.as_string().str != "auto")
      r.fail("dt", fmt::format("expected a number of seconds or \"auto\", got {}", describe(dt)));
    c.dt_auto = true;
  } else {
    c.dt = r.number(dt, "dt", "the time step in s, or \"auto\"");
    r.range_check("dt", c.dt, c.dt > 0, "(0, inf) s");
  }
  c.dt_safety = r.number_or("safety", c.dt_safety);
  r.range_check("safety", c.dt_safety, c.dt_safety > 0 && c.dt_safety <= 1,
                "(0, 1] (a fraction of the stability limit)");
  if (r.has("safety") && !c.dt_auto) r.fail("safety", "applies only with dt = \"auto\"");
  c.end = r.number("end", "the end time in s");
  r.range_check("end", c.end, c.end >= c.dt && c.end > 0,
                fmt::format("[dt, inf) = [{}, inf) s", c.dt));
  r.finish();
}

void read_output(TableReader& top, CaseSpec& c) {
  c.history_default = true;  // unless given below
  c.frame_interval = c.end / 10.0;
  c.checkpoint_interval = std::max(c.end / 4.0, c.dt);
  if (const TomlValue* table = top.subtable_or_null("output")) {
    TableReader r(*table, "output", top.file());
    c.frame_interval = r.number_or("frame_interval", c.frame_interval);
    r.range_check("frame_interval", c.frame_interval,
                  c.frame_interval >= c.dt && c.frame_interval > 0,
                  fmt::format("[dt, inf) = [{}, inf) s", c.dt));
    if (r.has("history_interval")) {
      c.history_default = false;
      c.history_interval = r.number("history_interval", "the history row interval in s");
      r.range_check("history_interval", c.history_interval,
                    c.history_interval >= c.dt && c.history_interval > 0 &&
                        c.history_interval <= c.frame_interval,
                    fmt::format("[dt, frame_interval] = [{}, {}] s", c.dt, c.frame_interval));
    }
    c.checkpoint_interval = r.number_or("checkpoint_interval", c.checkpoint_interval);
    r.range_check(
        "checkpoint_interval", c.checkpoint_interval,
        c.checkpoint_interval == 0 || (c.checkpoint_interval >= c.dt && c.checkpoint_interval > 0),
        fmt::format("0 (only at the end) or [dt, inf) = [{}, inf) s", c.dt));
    const double level = r.number_or("compression", 0);
    r.range_check("compression", level, level >= 0 && level <= 9 && level == std::floor(level),
                  "a deflate level 0 (off) to 9");
    c.compression = static_cast<int>(level);
    r.finish();
  }
  if (c.history_default) c.history_interval = c.default_history_interval();
}

// Every model's section is checked against its options table, whichever
// model is chosen; the chosen model's values are kept.
void read_model_sections(TableReader& top, const std::vector<ModelInfo>& models, CaseSpec& c) {
  for (const ModelInfo& model : models) {
    if (model.section.empty()) continue;
    const TomlValue* table = top.subtable_or_null(model.section);
    if (!table) continue;
    TableReader r(*table, model.section, top.file());
    OptionValues values;
    for (const OptionSpec& o : model.options) {
      if (o.is_choice()) {
        values.choices[o.key] = r.choice_or(o.key, o.choices, o.default_choice);
        continue;
      }
      const double v = r.number_or(o.key, o.default_number);
      r.range_check(o.key, v, o.valid(v), o.allowed);
      values.numbers[o.key] = v;
    }
    r.finish();
    if (model.section == c.model_section)
      c.model_options = values;
    else
      c.notes.push_back(
          fmt::format("[{}] sets options of model {}; this case runs model {}, so "
                      "they do not apply",
                      model.section, model.name, c.model));
  }
}

void read_stability(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("stability");
  if (!table) return;
  TableReader r(*table, "stability", top.file());
  StabilitySpec& s = c.stability;
  const double interval = r.number_or("check_interval", static_cast<double>(s.check_interval));
  r.range_check("check_interval", interval,
                interval >= 1 && interval <= 1e12 && interval == std::floor(interval),
                "a whole number of steps in [1, 1e12]");
  s.check_interval = static_cast<std::int64_t>(interval);
  s.max_speed = r.number_or("max_speed", s.max_speed);
  r.range_check("max_speed", s.max_speed, s.max_speed > 0, "(0, inf) dilatational wave speeds");
  s.min_jacobian = r.number_or("min_jacobian", s.min_jacobian);
  r.range_check("min_jacobian", s.min_jacobian, s.min_jacobian >= 0 && s.min_jacobian < 1,
                "[0, 1)");
  s.energy_tolerance = r.number_or("energy_tolerance", s.energy_tolerance);
  r.range_check("energy_tolerance", s.energy_tolerance, s.energy_tolerance > 0, "(0, inf)");
  r.finish();
}

// [contact]: off unless enabled; the stiffness defaults to the largest
// plane-strain bulk modulus lambda + mu of the contacting elastic bodies'
// materials (of any contacting body's when none is elastic).
void read_contact(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("contact");
  if (!table) return;
  TableReader r(*table, "contact", top.file());
  ContactSpec& k = c.contact;
  k.enabled = r.boolean_or("enabled", true);
  k.distance = r.number_or("distance", k.distance);
  // At least l0 / 2, so no particle slips between two surface particles l0
  // apart; at most 1.5 l0, so a body's own surface pairs (sqrt 5 l0 apart at
  // rest) repel only beyond a third in compression (MODEL.md section 8).
  r.range_check("distance", k.distance, k.distance >= 0.5 && k.distance <= 1.5,
                "[0.5, 1.5] lattice spacings l0");
  k.skin = r.number_or("skin", k.skin);
  r.range_check("skin", k.skin, k.skin > 0 && k.skin <= 2.0, "(0, 2] lattice spacings l0");
  k.min_distance = r.number_or("min_distance", k.min_distance);
  r.range_check("min_distance", k.min_distance, k.min_distance >= 0.5 && k.min_distance < 1,
                "[0.5, 1) contact distances");
  k.bodies.clear();
  if (const TomlValue* names = r.find("bodies")) {
    if (!names->is_array() || names->as_array().empty())
      r.fail("bodies",
             fmt::format("expected a non-empty array of body names, got {}", describe(*names)));
    for (const TomlValue& name : names->as_array()) {
      const std::string text = r.string(name, "bodies", "a body name");
      const auto it = std::find_if(c.bodies.begin(), c.bodies.end(),
                                   [&](const BodySpec& b) { return b.name == text; });
      if (it == c.bodies.end())
        r.fail("bodies",
               fmt::format("unknown body '{}' (allowed: {})", text, join(names_of(c.bodies))));
      k.bodies.push_back(static_cast<int>(it - c.bodies.begin()));
    }
    std::sort(k.bodies.begin(), k.bodies.end());
    if (std::adjacent_find(k.bodies.begin(), k.bodies.end()) != k.bodies.end())
      r.fail("bodies", "lists a body twice");
  } else {
    for (std::size_t b = 0; b < c.bodies.size(); ++b) k.bodies.push_back(static_cast<int>(b));
  }
  const bool any_moving = std::any_of(k.bodies.begin(), k.bodies.end(), [&](int b) {
    return c.bodies[static_cast<std::size_t>(b)].kind != Kind::wall;
  });
  if (k.enabled && !any_moving)
    r.fail("bodies", "lists only walls, which never move: contact would do nothing");
  double bulk = 0, bulk_elastic = 0;
  for (const int b : k.bodies) {
    const BodySpec& body = c.bodies[static_cast<std::size_t>(b)];
    const Material& m = c.materials[static_cast<std::size_t>(body.material)];
    // The bulk modulus: lambda + mu in plane strain, lambda + 2 mu / 3 in space.
    const double modulus = c.dimension == 3 ? m.lambda() + 2.0 * m.mu() / 3.0 : m.lambda() + m.mu();
    bulk = std::max(bulk, modulus);
    if (body.kind == Kind::elastic) bulk_elastic = std::max(bulk_elastic, modulus);
  }
  k.stiffness = r.number_or("stiffness", bulk_elastic > 0 ? bulk_elastic : bulk);
  r.range_check("stiffness", k.stiffness, k.stiffness > 0 && std::isfinite(k.stiffness),
                "(0, inf) Pa");
  r.finish();
}

void read_numerics(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("numerics");
  if (!table) return;
  TableReader r(*table, "numerics", top.file());
  c.flush_subnormals = r.boolean_or("flush_subnormals", c.flush_subnormals);
  r.finish();
}

CaseSpec build_case(const TomlValue& root, const std::string& file, const std::string& stem,
                    const std::vector<ModelInfo>& models) {
  if (!root.is_table()) throw InputError(fmt::format("{}: the case must be a TOML table", file));
  CaseSpec c;
  c.source = file;
  TableReader top(root, "", file);
  c.name = top.string_or("name", stem);
  if (c.name.empty() || c.name.find('/') != std::string::npos)
    top.fail("name", "must be a non-empty name without '/'");
  read_model(top, models, c);
  const double dimension = top.number_or("dimension", 2);
  top.range_check("dimension", dimension, dimension == 2 || dimension == 3,
                  "2 (plane strain) or 3 (space)");
  c.dimension = static_cast<int>(dimension);
  c.l0 = top.number("l0", "the lattice spacing in m");
  top.range_check("l0", c.l0, c.l0 > 0, "(0, inf) m");
  if (c.dimension == 3 && top.has("depth"))
    top.fail("depth", "a body in space (dimension = 3) has its own extent in z: no depth");
  c.depth = top.number_or("depth", 1.0);
  top.range_check("depth", c.depth, c.depth > 0, "(0, inf) m");
  read_materials(top, c);
  read_bodies(top, c);
  read_loads(top, c);
  read_damping(top, c);
  read_probes(top, c);
  read_time(top, c);
  read_output(top, c);
  read_model_sections(top, models, c);
  read_stability(top, c);
  read_contact(top, c);
  read_gas(top, c);
  read_numerics(top, c);
  top.finish();
  if (!c.dt_auto) {
    c.snap_default_history();
    for (std::string& note : c.check_step_grid()) c.notes.push_back(std::move(note));
  }
  c.resolved_toml = resolved_case_toml(c);
  return c;
}

}  // namespace

CaseSpec parse_case(const std::string& toml_text, const std::string& source_name,
                    const std::vector<std::string>& overrides,
                    const std::vector<ModelInfo>& models) {
  TomlValue root;
  try {
    std::istringstream in(toml_text);
    root = toml::parse<toml::discard_comments, std::map, std::vector>(in, source_name);
  } catch (const toml::syntax_error& e) {
    throw InputError(fmt::format("{}: TOML syntax error:\n{}", source_name, e.what()));
  }
  apply_overrides(root, overrides);
  return build_case(root, source_name, std::filesystem::path(source_name).stem().string(), models);
}

CaseSpec read_case(const std::string& path, const std::vector<std::string>& overrides,
                   const std::vector<ModelInfo>& models) {
  if (std::filesystem::is_directory(path))
    throw InputError(
        fmt::format("{}: is a folder, not a case file (give the .toml file, e.g. "
                    "cases/shock_rod.toml)",
                    path));
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(fmt::format(
        "{}: cannot open the case file ({})", path,
        std::filesystem::exists(path) ? "permission denied or not a file" : "no such file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_case(text.str(), path, overrides, models);
}

}  // namespace mpsolid
