#include "src/case/case_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "kernels/model_registry.hpp"
#include "src/case/case_overrides.hpp"
#include "src/core/geometry.hpp"

namespace mpsolid {

namespace {

// Bond indices are 32-bit, with up to 12 (and a few spare) entries per particle.
constexpr double kMaxParticles =
    static_cast<double>(std::numeric_limits<std::uint32_t>::max() / 16);

// Where a value came from: "file:line" or "--set key=value".
std::string origin(const TomlValue& v, const std::string& file) {
  const auto loc = v.location();
  const std::string& name = loc.file_name();
  if (name.rfind("--set", 0) == 0) return name;
  if (name != "unknown file") return fmt::format("{}:{}", name, loc.line());
  // A table made by an override has no location of its own: its entries do.
  if (v.is_table())
    for (const auto& [key, entry] : v.as_table()) {
      const std::string inner = origin(entry, file);
      if (inner != file) return inner;
    }
  return file;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

std::string describe(const TomlValue& v) {
  std::string text = toml::format(v);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

// Reads one table, remembering which keys were used; finish() rejects the rest.
class TableReader {
 public:
  TableReader(const TomlValue& table, std::string path, const std::string& file)
      : table_(table), path_(std::move(path)), file_(file) {}

  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    const auto& entries = table_.as_table();
    const auto it = entries.find(key);
    const std::string where = it != entries.end() ? origin(it->second, file_) : file_;
    throw InputError(fmt::format("{}: {}: {}", where, key_path(key), problem));
  }

  const TomlValue* find(const std::string& key) {
    used_.insert(key);
    const auto& entries = table_.as_table();
    const auto it = entries.find(key);
    return it == entries.end() ? nullptr : &it->second;
  }

  const TomlValue& require(const std::string& key, const std::string& what) {
    const TomlValue* v = find(key);
    if (!v) throw InputError(fmt::format("{}: {} is missing ({})", file_, key_path(key), what));
    return *v;
  }

  static bool is_number(const TomlValue& v) { return v.is_floating() || v.is_integer(); }
  static double as_number(const TomlValue& v) {
    return v.is_floating() ? v.as_floating() : static_cast<double>(v.as_integer());
  }

  double number(const TomlValue& v, const std::string& key, const std::string& what = "") const {
    if (!is_number(v))
      fail(key, fmt::format("expected a number{}, got {} ({})", detail(what), describe(v),
                            type_name(v)));
    const double x = as_number(v);
    if (!std::isfinite(x)) fail(key, fmt::format("expected a finite number, got {}", x));
    return x;
  }

  double number(const std::string& key, const std::string& what) {
    return number(require(key, what), key, what);
  }
  double number_or(const std::string& key, double fallback) {
    const TomlValue* v = find(key);
    return v ? number(*v, key) : fallback;
  }

  std::string string(const TomlValue& v, const std::string& key,
                     const std::string& what = "") const {
    if (!v.is_string())
      fail(key, fmt::format("expected a string{}, got {} ({})", detail(what), describe(v),
                            type_name(v)));
    return v.as_string().str;
  }
  std::string string(const std::string& key, const std::string& what) {
    return string(require(key, what), key, what);
  }
  bool boolean_or(const std::string& key, bool fallback) {
    const TomlValue* v = find(key);
    if (!v) return fallback;
    if (!v->is_boolean()) fail(key, fmt::format("expected true or false, got {}", describe(*v)));
    return v->as_boolean();
  }

  std::string string_or(const std::string& key, const std::string& fallback) {
    const TomlValue* v = find(key);
    return v ? string(*v, key) : fallback;
  }

  // [a, b] with two numbers.
  void pair(const std::string& key, const std::string& what, double out[2]) {
    const TomlValue& v = require(key, what);
    if (!v.is_array() || v.as_array().size() != 2 || !is_number(v.as_array()[0]) ||
        !is_number(v.as_array()[1]))
      fail(key, fmt::format("expected two numbers [a, b] ({}), got {}", what, describe(v)));
    out[0] = number(v.as_array()[0], key);
    out[1] = number(v.as_array()[1], key);
  }

  // [a, b] if the key is present; `out` keeps its value otherwise.
  void pair_or(const std::string& key, const std::string& what, double out[2]) {
    if (has(key)) pair(key, what, out);
  }
  bool has(const std::string& key) const { return table_.as_table().count(key) > 0; }

  const TomlValue& subtable(const std::string& key, const std::string& what) {
    const TomlValue& v = require(key, what);
    if (!v.is_table()) fail(key, fmt::format("expected a table ({})", what));
    return v;
  }
  const TomlValue* subtable_or_null(const std::string& key) {
    const TomlValue* v = find(key);
    if (v && !v->is_table()) fail(key, "expected a table");
    return v;
  }

  void range_check(const std::string& key, double value, bool ok, const std::string& allowed) {
    if (!ok) fail(key, fmt::format("{} is outside the allowed range {}", value, allowed));
  }

  void finish(const std::vector<std::string>& allowed) const {
    for (const auto& [key, value] : table_.as_table()) {
      if (used_.count(key)) continue;
      throw InputError(fmt::format("{}: {}: unknown key (allowed here: {})", origin(value, file_),
                                   key_path(key), join(allowed)));
    }
  }

  const std::string& file() const { return file_; }

 private:
  static std::string detail(const std::string& what) {
    return what.empty() ? "" : " (" + what + ")";
  }
  static std::string type_name(const TomlValue& v) {
    std::ostringstream s;
    s << v.type();
    return s.str();
  }

  const TomlValue& table_;
  std::string path_;
  const std::string& file_;
  std::set<std::string> used_;
};

Kind parse_kind(TableReader& r, const std::string& key, const std::string& text) {
  if (text == "elastic") return Kind::elastic;
  if (text == "rigid") return Kind::rigid;
  if (text == "wall") return Kind::wall;
  r.fail(key, fmt::format("unknown kind '{}' (allowed: elastic, rigid, wall)", text));
}

std::string format_number(double x) {
  return fmt::format("{:.17g}", x);
}
std::string quote(const std::string& text) {
  return toml::format(TomlValue(text));
}
std::string key(const std::string& name) {
  return toml::format_key(name);
}

Hold parse_hold(TableReader& r, const std::string& key, const std::string& text) {
  if (text == "none") return Hold::none;
  if (text == "x") return Hold::x;
  if (text == "y") return Hold::y;
  r.fail(key, fmt::format("unknown hold '{}' (allowed: none, x, y)", text));
}
const char* hold_name(Hold hold) {
  return hold == Hold::x ? "x" : hold == Hold::y ? "y" : "none";
}

std::string body_toml(const CaseSpec& c, const BodySpec& b) {
  std::string out = fmt::format(
      "\n[bodies.{}]\nkind = \"{}\"\nmaterial = {}\nx = [{}, {}]\ny = [{}, {}]\n", key(b.name),
      kind_name(b.kind), quote(c.materials[static_cast<std::size_t>(b.material)].name),
      format_number(b.x[0]), format_number(b.x[1]), format_number(b.y[0]), format_number(b.y[1]));
  // Initial motion and holds only where set: walls accept none of them.
  if (b.velocity[0] != 0 || b.velocity[1] != 0)
    out += fmt::format("velocity = [{}, {}]\n", format_number(b.velocity[0]),
                       format_number(b.velocity[1]));
  if (b.spin != 0) out += fmt::format("spin = {}\n", format_number(b.spin));
  if (b.hold != Hold::none) out += fmt::format("hold = \"{}\"\n", hold_name(b.hold));
  if (b.has_mode)
    out += fmt::format(
        "\n[bodies.{}.bending_mode]\nroot_x = {}\nlength = {}\nkL = {}\ntip_velocity = {}\n",
        key(b.name), format_number(b.mode.root_x), format_number(b.mode.length),
        format_number(b.mode.kl), format_number(b.mode.tip_velocity));
  return out;
}

std::string time_toml(const CaseSpec& c) {
  if (c.dt_auto && c.dt == 0)
    return fmt::format("\n[time]\ndt = \"auto\"\nsafety = {}\nend = {}\n",
                       format_number(c.dt_safety), format_number(c.end));
  return fmt::format("\n[time]\ndt = {}\nend = {}\n", format_number(c.dt), format_number(c.end));
}

// velocity, spin, hold and bending_mode of a [bodies.NAME] table.
void read_body_motion(TableReader& r, BodySpec& b) {
  const bool wall = b.kind == Kind::wall;
  for (const char* k : {"velocity", "spin", "hold", "bending_mode"})
    if (wall && r.has(k)) r.fail(k, "walls never move: a wall takes no initial motion or hold");
  r.pair_or("velocity", "the initial velocity [vx, vy] in m/s", b.velocity);
  b.spin = r.number_or("spin", 0.0);
  b.hold = parse_hold(r, "hold", r.string_or("hold", "none"));
  if (b.kind == Kind::rigid && b.hold != Hold::none)
    r.fail("hold", "a rigid body cannot be held (use a wall for a fixed body)");
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
    m.finish({"root_x", "length", "kL", "tip_velocity"});
  }
}

// Calls each(name, value, reader) for every [SECTION.NAME] entry, in name
// order; an entry that is not a table is refused with what it should hold.
template <class Each>
void for_each_named_table(const TomlValue& section, const std::string& section_name,
                          const std::string& file, const char* holds, Each&& each) {
  for (const auto& [name, value] : section.as_table()) {
    if (!value.is_table())
      throw InputError(fmt::format("{}: {}.{}: expected a table with {}", origin(value, file),
                                   section_name, name, holds));
    TableReader r(value, section_name + "." + name, file);
    each(name, value, r);
  }
}

bool rectangles_overlap(const BodySpec& a, const BodySpec& b) {
  return a.x[0] < b.x[1] && b.x[0] < a.x[1] && a.y[0] < b.y[1] && b.y[0] < a.y[1];
}

CaseSpec build_case(const TomlValue& root, const std::string& file, const std::string& stem) {
  if (!root.is_table()) throw InputError(fmt::format("{}: the case must be a TOML table", file));
  CaseSpec c;
  c.source = file;
  TableReader top(root, "", file);

  c.name = top.string_or("name", stem);
  if (c.name.empty() || c.name.find('/') != std::string::npos)
    top.fail("name", "must be a non-empty name without '/'");
  c.model = top.string_or("model", "paper");
  const auto& models = model_names();
  if (std::find(models.begin(), models.end(), c.model) == models.end())
    top.fail("model", fmt::format("unknown model '{}' (allowed: {})", c.model, join(models)));
  c.l0 = top.number("l0", "the lattice spacing in m");
  top.range_check("l0", c.l0, c.l0 > 0, "(0, inf) m");
  c.depth = top.number_or("depth", 1.0);
  top.range_check("depth", c.depth, c.depth > 0, "(0, inf) m");

  // Materials.
  std::map<std::string, int> material_index;
  {
    const TomlValue& table = top.subtable("materials", "one [materials.NAME] table per material");
    if (table.as_table().empty())
      throw InputError(fmt::format("{}: materials: at least one material is needed", file));
    for_each_named_table(
        table, "materials", file, "E, nu, rho",
        [&](const std::string& name, const TomlValue&, TableReader& r) {
          Material m;
          m.name = name;
          m.youngs_modulus = r.number("E", "Young's modulus in Pa");
          r.range_check("E", m.youngs_modulus, m.youngs_modulus > 0, "(0, inf) Pa");
          m.poisson_ratio = r.number("nu", "Poisson's ratio");
          r.range_check("nu", m.poisson_ratio, m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5,
                        "(-1, 0.5)");
          m.density = r.number("rho", "density in kg/m^3");
          r.range_check("rho", m.density, m.density > 0, "(0, inf) kg/m^3");
          r.finish({"E", "nu", "rho"});
          material_index[name] = static_cast<int>(c.materials.size());
          c.materials.push_back(m);
        });
  }

  // Bodies.
  std::map<std::string, int> body_index;
  std::int64_t particle_total = 0;
  {
    const TomlValue& table = top.subtable("bodies", "one [bodies.NAME] table per body");
    if (table.as_table().empty())
      throw InputError(fmt::format("{}: bodies: at least one body is needed", file));
    for_each_named_table(
        table, "bodies", file, "kind, material, x, y",
        [&](const std::string& name, const TomlValue& value, TableReader& r) {
          BodySpec b;
          b.name = name;
          b.kind = parse_kind(r, "kind", r.string("kind", "elastic, rigid or wall"));
          const std::string material = r.string("material", "the name of a [materials.NAME] table");
          if (!material_index.count(material))
            r.fail("material",
                   fmt::format("no material named '{}' (defined: {})", material, join([&] {
                                 std::vector<std::string> names;
                                 for (const auto& m : c.materials) names.push_back(m.name);
                                 return names;
                               }())));
          b.material = material_index[material];
          r.pair("x", "the rectangle's x range [x0, x1] in m", b.x);
          r.pair("y", "the rectangle's y range [y0, y1] in m", b.y);
          if (!(b.x[0] < b.x[1]))
            r.fail("x", fmt::format("needs x0 < x1, got [{}, {}]", b.x[0], b.x[1]));
          if (!(b.y[0] < b.y[1]))
            r.fail("y", fmt::format("needs y0 < y1, got [{}, {}]", b.y[0], b.y[1]));
          read_body_motion(r, b);
          r.finish({"kind", "material", "x", "y", "velocity", "spin", "hold", "bending_mode"});
          // Estimate in floating point first: integer lattice indices would
          // overflow for an absurdly small l0.
          const double estimate =
              ((b.x[1] - b.x[0]) / c.l0 + 1.0) * ((b.y[1] - b.y[0]) / c.l0 + 1.0);
          if (!(estimate < kMaxParticles))
            top.fail("l0",
                     fmt::format("l0 = {} m gives about {:.3g} particles in bodies.{}, more than "
                                 "this build supports ({} particles)",
                                 c.l0, estimate, name, kMaxParticles));
          const std::int64_t sites = lattice_span(b.x[0], b.x[1], c.l0).count() *
                                     lattice_span(b.y[0], b.y[1], c.l0).count();
          if (sites == 0)
            throw InputError(
                fmt::format("{}: bodies.{}: the body is empty: no lattice site (centre at (k + "
                            "1/2) l0, l0 = {} m) "
                            "lies in x = [{}, {}), y = [{}, {})",
                            origin(value, file), name, c.l0, b.x[0], b.x[1], b.y[0], b.y[1]));
          particle_total += sites;
          body_index[name] = static_cast<int>(c.bodies.size());
          c.bodies.push_back(b);
        });
    for (std::size_t a = 0; a < c.bodies.size(); ++a)
      for (std::size_t b = a + 1; b < c.bodies.size(); ++b)
        if (rectangles_overlap(c.bodies[a], c.bodies[b]))
          throw InputError(fmt::format(
              "{}: bodies.{} and bodies.{} overlap (x = [{}, {}], y = [{}, {}] and x = [{}, {}], "
              "y = [{}, {}]); bodies may touch but not overlap",
              file, c.bodies[a].name, c.bodies[b].name, c.bodies[a].x[0], c.bodies[a].x[1],
              c.bodies[a].y[0], c.bodies[a].y[1], c.bodies[b].x[0], c.bodies[b].x[1],
              c.bodies[b].y[0], c.bodies[b].y[1]));
    if (static_cast<double>(particle_total) >= kMaxParticles)
      top.fail("l0", fmt::format("l0 = {} m gives {} particles, more than this build supports ({} "
                                 "particles)",
                                 c.l0, particle_total, kMaxParticles));
  }

  // Loads.
  if (const TomlValue* table = top.subtable_or_null("loads")) {
    for_each_named_table(
        *table, "loads", file, "body, force, start",
        [&](const std::string& name, const TomlValue&, TableReader& r) {
          LoadSpec l;
          l.name = name;
          const std::string type = r.string_or("type", "step");
          if (type != "step")
            r.fail("type", fmt::format("unknown load type '{}' (allowed: step)", type));
          const std::string body = r.string("body", "the name of a [bodies.NAME] table");
          if (!body_index.count(body)) {
            std::vector<std::string> names;
            for (const auto& b : c.bodies) names.push_back(b.name);
            r.fail("body", fmt::format("no body named '{}' (defined: {})", body, join(names)));
          }
          l.body = body_index[body];
          if (c.bodies[static_cast<std::size_t>(l.body)].kind == Kind::wall)
            r.fail("body",
                   fmt::format("'{}' is a wall; walls do not move, so a load on it does nothing",
                               body));
          r.pair("force", "the total force [Fx, Fy] in N (over the depth)", l.force);
          l.start = r.number_or("start", 0.0);
          r.range_check("start", l.start, l.start >= 0, "[0, inf) s");
          r.finish({"type", "body", "force", "start"});
          c.loads.push_back(l);
        });
  }

  // Probes.
  if (const TomlValue* table = top.subtable_or_null("probes")) {
    for_each_named_table(
        *table, "probes", file, "at = [x, y]",
        [&](const std::string& name, const TomlValue&, TableReader& r) {
          ProbeSpec probe;
          probe.name = name;
          r.pair("at", "the initial point [x, y] in m whose nearest particle is followed",
                 probe.at);
          // A point off every body is a typo, not a request to follow a far particle.
          const bool on_a_body =
              std::any_of(c.bodies.begin(), c.bodies.end(), [&](const BodySpec& b) {
                return probe.at[0] >= b.x[0] - c.l0 && probe.at[0] <= b.x[1] + c.l0 &&
                       probe.at[1] >= b.y[0] - c.l0 && probe.at[1] <= b.y[1] + c.l0;
              });
          if (!on_a_body)
            r.fail("at", fmt::format("[{}, {}] is not within l0 = {} m of any body", probe.at[0],
                                     probe.at[1], c.l0));
          r.finish({"at"});
          c.probes.push_back(probe);
        });
  }

  // Time. With dt = "auto" the step is not known yet: intervals are checked
  // against 0 here, and whole-step cadences are kept at >= 1 step.
  {
    const TomlValue& table = top.subtable("time", "[time] with dt and end");
    TableReader r(table, "time", file);
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
    r.finish({"dt", "safety", "end"});
  }

  // Output.
  c.frame_interval = c.end / 10.0;
  c.checkpoint_interval = std::max(c.end / 4.0, c.dt);
  if (const TomlValue* table = top.subtable_or_null("output")) {
    TableReader r(*table, "output", file);
    c.frame_interval = r.number_or("frame_interval", c.frame_interval);
    r.range_check("frame_interval", c.frame_interval,
                  c.frame_interval >= c.dt && c.frame_interval > 0,
                  fmt::format("[dt, inf) = [{}, inf) s", c.dt));
    c.history_interval = r.number_or("history_interval", c.frame_interval);
    r.range_check("history_interval", c.history_interval,
                  c.history_interval >= c.dt && c.history_interval > 0 &&
                      c.history_interval <= c.frame_interval,
                  fmt::format("[dt, frame_interval] = [{}, {}] s", c.dt, c.frame_interval));
    c.checkpoint_interval = r.number_or("checkpoint_interval", c.checkpoint_interval);
    r.range_check(
        "checkpoint_interval", c.checkpoint_interval,
        c.checkpoint_interval == 0 || (c.checkpoint_interval >= c.dt && c.checkpoint_interval > 0),
        fmt::format("0 (only at the end) or [dt, inf) = [{}, inf) s", c.dt));
    const double level = r.number_or("compression", 0);
    r.range_check("compression", level, level >= 0 && level <= 9 && level == std::floor(level),
                  "a deflate level 0 (off) to 9");
    c.compression = static_cast<int>(level);
    r.finish({"frame_interval", "history_interval", "checkpoint_interval", "compression"});
  }
  if (c.history_interval == 0) c.history_interval = c.frame_interval;

  // Model options.
  if (const TomlValue* table = top.subtable_or_null("finite_strain")) {
    TableReader r(*table, "finite_strain", file);
    c.model_options.hourglass = r.number_or("hourglass", c.model_options.hourglass);
    r.range_check("hourglass", c.model_options.hourglass, c.model_options.hourglass >= 0,
                  "[0, inf) (0 switches the penalty off)");
    const std::string form = r.string_or("hourglass_form", "consistent");
    if (form != "consistent" && form != "frozen")
      r.fail("hourglass_form",
             fmt::format("unknown form '{}' (allowed: consistent, frozen)", form));
    c.model_options.consistent_hourglass = form == "consistent";
    r.finish({"hourglass", "hourglass_form"});
  }

  // Blow-up checks.
  if (const TomlValue* table = top.subtable_or_null("stability")) {
    TableReader r(*table, "stability", file);
    const double interval =
        r.number_or("check_interval", static_cast<double>(c.stability.check_interval));
    r.range_check("check_interval", interval,
                  interval >= 1 && interval <= 1e12 && interval == std::floor(interval),
                  "a whole number of steps in [1, 1e12]");
    c.stability.check_interval = static_cast<std::int64_t>(interval);
    c.stability.max_speed = r.number_or("max_speed", c.stability.max_speed);
    r.range_check("max_speed", c.stability.max_speed, c.stability.max_speed > 0,
                  "(0, inf) dilatational wave speeds");
    c.model_options.min_jacobian = r.number_or("min_jacobian", c.model_options.min_jacobian);
    r.range_check("min_jacobian", c.model_options.min_jacobian,
                  c.model_options.min_jacobian >= 0 && c.model_options.min_jacobian < 1, "[0, 1)");
    c.stability.energy_tolerance = r.number_or("energy_tolerance", c.stability.energy_tolerance);
    r.range_check("energy_tolerance", c.stability.energy_tolerance,
                  c.stability.energy_tolerance > 0, "(0, inf)");
    r.finish({"check_interval", "max_speed", "min_jacobian", "energy_tolerance"});
  }

  if (const TomlValue* table = top.subtable_or_null("numerics")) {
    TableReader r(*table, "numerics", file);
    c.flush_subnormals = r.boolean_or("flush_subnormals", c.flush_subnormals);
    r.finish({"flush_subnormals"});
  }

  top.finish({"name", "model", "l0", "depth", "materials", "bodies", "loads", "probes", "time",
              "output", "finite_strain", "stability", "numerics"});
  c.resolved_toml = resolved_case_toml(c);
  return c;
}

}  // namespace

// Derived figures go in as comments.
std::string resolved_case_toml(const CaseSpec& c) {
  std::string out = fmt::format(
      "# Resolved by mpsolid from {}.\n# Derived: re = {} m, particle volume V = {} m^3\n",
      c.source, format_number(2.1 * c.l0), format_number(c.l0 * c.l0 * c.depth));
  for (const auto& m : c.materials)
    out += fmt::format("# material {}: lambda = {} Pa, mu = {} Pa\n", key(m.name),
                       format_number(m.lambda()), format_number(m.mu()));
  out += fmt::format("\nname = {}\nmodel = {}\nl0 = {}\ndepth = {}\n", quote(c.name),
                     quote(c.model), format_number(c.l0), format_number(c.depth));
  for (const auto& m : c.materials)
    out += fmt::format("\n[materials.{}]\nE = {}\nnu = {}\nrho = {}\n", key(m.name),
                       format_number(m.youngs_modulus), format_number(m.poisson_ratio),
                       format_number(m.density));
  for (const auto& b : c.bodies) out += body_toml(c, b);
  for (const auto& l : c.loads)
    out +=
        fmt::format("\n[loads.{}]\ntype = \"step\"\nbody = {}\nforce = [{}, {}]\nstart = {}\n",
                    key(l.name), quote(c.bodies[static_cast<std::size_t>(l.body)].name),
                    format_number(l.force[0]), format_number(l.force[1]), format_number(l.start));
  for (const auto& probe : c.probes)
    out += fmt::format("\n[probes.{}]\nat = [{}, {}]\n", key(probe.name),
                       format_number(probe.at[0]), format_number(probe.at[1]));
  out += time_toml(c);
  out += fmt::format("\n[output]\nframe_interval = {}\nhistory_interval = {}\n",
                     format_number(c.frame_interval), format_number(c.history_interval));
  out += fmt::format("checkpoint_interval = {}\ncompression = {}\n",
                     format_number(c.checkpoint_interval), c.compression);
  out += fmt::format("\n[finite_strain]\nhourglass = {}\nhourglass_form = \"{}\"\n",
                     format_number(c.model_options.hourglass),
                     c.model_options.consistent_hourglass ? "consistent" : "frozen");
  out += fmt::format(
      "\n[stability]\ncheck_interval = {}\nmax_speed = {}\nmin_jacobian = {}\nenergy_tolerance = "
      "{}\n",
      c.stability.check_interval, format_number(c.stability.max_speed),
      format_number(c.model_options.min_jacobian), format_number(c.stability.energy_tolerance));
  out += fmt::format("\n[numerics]\nflush_subnormals = {}\n", c.flush_subnormals);
  return out;
}

std::int64_t CaseSpec::step_count() const {
  // Nearest whole step when end is a multiple of dt up to round-off, else the
  // first step at or past end.
  const double ratio = end / dt;
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio))
    return static_cast<std::int64_t>(nearest);
  return static_cast<std::int64_t>(std::ceil(ratio));
}

namespace {
// Whole steps in `interval`: the nearest count when it is a multiple of dt up
// to round-off, else rounded down; at least 1.
std::int64_t steps_in(double interval, double dt) {
  const double ratio = interval / dt;
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio))
    return std::max<std::int64_t>(1, static_cast<std::int64_t>(nearest));
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(ratio)));
}
}  // namespace

std::int64_t CaseSpec::steps_per_checkpoint() const {
  return checkpoint_interval > 0 ? steps_in(checkpoint_interval, dt) : 0;
}
std::int64_t CaseSpec::steps_per_frame() const {
  return steps_in(frame_interval, dt);
}
std::int64_t CaseSpec::steps_per_history() const {
  return std::min(steps_per_frame(), steps_in(history_interval, dt));
}

void CaseSpec::set_auto_time_step(double limit, double omega_max) {
  // The finest output interval becomes a whole number of steps, so outputs
  // fall on the requested times whatever step is chosen.
  const double finest = std::min(history_interval, frame_interval);
  const double target = dt_safety * limit;
  dt = finest / std::ceil(finest / target * (1.0 - 1e-12));
  // The resolved case keeps the chosen step as a number, so a resumed run
  // goes on with it rather than estimating again.
  resolved_toml = fmt::format(
      "# time.dt = \"auto\" chose {} s: the largest step <= safety {} x the model's stability\n"
      "# limit 2 / omega_max = {} s (omega_max = {} rad/s) with whole steps per output.\n",
      format_number(dt), format_number(dt_safety), format_number(limit), format_number(omega_max));
  resolved_toml += resolved_case_toml(*this);
  if (checkpoint_interval > 0) checkpoint_interval = std::max(checkpoint_interval, dt);
}

CaseSpec parse_case(const std::string& toml_text, const std::string& source_name,
                    const std::vector<std::string>& overrides) {
  TomlValue root;
  try {
    std::istringstream in(toml_text);
    root = toml::parse<toml::discard_comments, std::map, std::vector>(in, source_name);
  } catch (const toml::syntax_error& e) {
    throw InputError(fmt::format("{}: TOML syntax error:\n{}", source_name, e.what()));
  }
  apply_overrides(root, overrides);
  return build_case(root, source_name, std::filesystem::path(source_name).stem().string());
}

CaseSpec read_case(const std::string& path, const std::vector<std::string>& overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(fmt::format(
        "{}: cannot open the case file ({})", path,
        std::filesystem::exists(path) ? "permission denied or not a file" : "no such file"));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_case(text.str(), path, overrides);
}

}  // namespace mpsolid
