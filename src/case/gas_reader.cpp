#include "src/case/gas_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "src/case/shape_reader.hpp"

namespace mpsolid {

namespace {

// More cells than this is a typo in `cell`, not a run (each cell holds 24
// doubles: about 19 GB).
constexpr double kMaxGasCells = 1e8;

GasSpec::Edge parse_edge(TableReader& r, const char* key) {
  const std::string kind = r.choice_or(key, {"slip_wall", "inflow", "outflow"}, "slip_wall");
  return kind == "inflow"    ? GasSpec::Edge::inflow
         : kind == "outflow" ? GasSpec::Edge::outflow
                             : GasSpec::Edge::slip_wall;
}

GasStateSpec read_state(TableReader& r) {
  GasStateSpec s;
  s.density = r.number("density", "the gas's density in kg/m^3");
  r.range_check("density", s.density, s.density > 0 && std::isfinite(s.density), "(0, inf) kg/m^3");
  s.pressure = r.number("pressure", "the gas's pressure in Pa");
  r.range_check("pressure", s.pressure, s.pressure > 0 && std::isfinite(s.pressure), "(0, inf) Pa");
  r.pair_or("velocity", "the gas's velocity [ux, uy] in m/s", s.velocity);
  for (const double u : s.velocity) r.range_check("velocity", u, std::isfinite(u), "finite m/s");
  return s;
}

// The outline's edges of a shape: its region's and its holes' (an
// annulus's inner circle too).
std::vector<std::vector<Point2>> outlines(const Shape& shape) {
  std::vector<std::vector<Point2>> loops{region_outline(shape.region)};
  if (const auto* a = std::get_if<AnnulusRegion>(&shape.region))
    loops.push_back(region_outline(CircleRegion{a->center, a->inner}));
  for (const Region& hole : shape.holes) loops.push_back(region_outline(hole));
  return loops;
}

double distance_to_nearest_crossing(const std::vector<std::vector<Point2>>& loops, Point2 from,
                                    Point2 direction, const Point2* skip_a, const Point2* skip_b) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& loop : loops)
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Point2& a = loop[k];
      const Point2& b = loop[(k + 1) % loop.size()];
      if (&a == skip_a && &b == skip_b) continue;
      // from + s direction = a + t (b - a), s > 0, t in [0, 1].
      const double ex = b.x - a.x, ey = b.y - a.y;
      const double det = direction.x * (-ey) - direction.y * (-ex);
      if (std::abs(det) < 1e-300) continue;
      const double rx = a.x - from.x, ry = a.y - from.y;
      const double s = (rx * (-ey) - ry * (-ex)) / det;
      const double t = (direction.x * ry - direction.y * rx) / det;
      if (s > 0 && t >= 0 && t <= 1) best = std::min(best, s);
    }
  return best;
}

// Every body in c whose bounds overlap the grid.
std::vector<int> bodies_over_grid(const CaseSpec& c) {
  std::vector<int> out;
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    const Box2 box = c.bodies[b].shape.bounds();
    if (box.hi.x > c.gas.x[0] && box.lo.x < c.gas.x[1] && box.hi.y > c.gas.y[0] &&
        box.lo.y < c.gas.y[1])
      out.push_back(static_cast<int>(b));
  }
  return out;
}

void read_grid(TableReader& r, GasSpec& g) {
  g.gamma = r.number_or("gamma", g.gamma);
  r.range_check("gamma", g.gamma, g.gamma > 1 && g.gamma < 10, "(1, 10)");
  g.cell = r.number("cell", "the gas cells' side in m");
  r.range_check("cell", g.cell, g.cell > 0 && std::isfinite(g.cell), "(0, inf) m");
  double cells = 1;
  for (const char* key : {"x", "y"}) {
    double* span = key[0] == 'x' ? g.x : g.y;
    r.pair(key, fmt::format("the grid's {} range [{}0, {}1] in m", key, key, key), span);
    if (!(span[0] < span[1]))
      r.fail(key, fmt::format("needs {}0 < {}1, got [{}, {}]", key, key, span[0], span[1]));
    const double n = (span[1] - span[0]) / g.cell;
    if (std::abs(n - std::round(n)) > 1e-6 * std::max(1.0, n))
      r.fail(key, fmt::format("spans {:.6g} cells of {} m: the grid needs a whole number (make "
                              "{}1 - {}0 a multiple of gas.cell)",
                              n, g.cell, key, key));
    cells *= std::round(n);
  }
  if (cells > kMaxGasCells)
    r.fail("cell", fmt::format("gives {:.4g} gas cells, more than {:.0e}", cells, kMaxGasCells));
  g.cfl = r.number_or("cfl", g.cfl);
  r.range_check("cfl", g.cfl, g.cfl > 0 && g.cfl <= 1, "(0, 1]");
  const char* edges[2][2] = {{"left", "right"}, {"bottom", "top"}};
  for (int a = 0; a < 2; ++a)
    for (int side = 0; side < 2; ++side) g.edges[a][side] = parse_edge(r, edges[a][side]);
}

void read_shock(TableReader& gas, GasSpec& g) {
  const TomlValue* table = gas.subtable_or_null("shock");
  if (!table) return;
  TableReader r(*table, gas.key_path("shock"), gas.file());
  g.mach = r.number("mach", "the shock's Mach number against the gas ahead of it");
  r.range_check("mach", g.mach, g.mach > 1 && g.mach < 50, "(1, 50)");
  g.shock_x = r.number("x", "where the shock is at t = 0, in m");
  r.range_check("x", g.shock_x, g.shock_x > g.x[0] && g.shock_x < g.x[1],
                fmt::format("({}, {}) m: inside the grid", g.x[0], g.x[1]));
  const std::string direction = r.choice_or("direction", {"+x", "-x"}, "+x");
  g.direction = direction == "+x" ? 1 : -1;
  if (g.initial.velocity[0] != 0 || g.initial.velocity[1] != 0)
    r.fail("mach", "a shock runs into gas at rest: gas.initial.velocity must be [0, 0]");
  r.finish();
}

void read_coupled_bodies(TableReader& r, CaseSpec& c) {
  GasSpec& g = c.gas;
  const std::vector<int> over = bodies_over_grid(c);
  if (const TomlValue* names = r.find("bodies")) {
    if (!names->is_array())
      r.fail("bodies", fmt::format("expected an array of body names, got {}", describe(*names)));
    for (const TomlValue& name : names->as_array()) {
      const std::string text = r.string(name, "bodies", "a body name");
      const auto it = std::find_if(c.bodies.begin(), c.bodies.end(),
                                   [&](const BodySpec& b) { return b.name == text; });
      if (it == c.bodies.end()) r.fail("bodies", fmt::format("unknown body '{}'", text));
      const int b = static_cast<int>(it - c.bodies.begin());
      if (std::find(over.begin(), over.end(), b) == over.end())
        r.fail("bodies", fmt::format("body '{}' lies outside the gas grid [{}, {}] x [{}, {}] m: "
                                     "the grid must cover the bodies the gas pushes",
                                     text, g.x[0], g.x[1], g.y[0], g.y[1]));
      g.bodies.push_back(b);
    }
    std::sort(g.bodies.begin(), g.bodies.end());
    if (std::adjacent_find(g.bodies.begin(), g.bodies.end()) != g.bodies.end())
      r.fail("bodies", "lists a body twice");
  } else {
    g.bodies = over;
  }
  for (const int b : g.bodies) {
    const BodySpec& body = c.bodies[static_cast<std::size_t>(b)];
    const double width = thinnest_width(body.shape);
    if (g.cell > width * (1 + 1e-9))
      r.fail("cell", fmt::format("{} m is coarser than body '{}' is thin ({:.6g} m): a gas cell "
                                 "must be at most the thinnest coupled body's width, or gas "
                                 "cells could change sides through it",
                                 g.cell, body.name, width));
  }
}

void read_probes(TableReader& gas, GasSpec& g) {
  const TomlValue* table = gas.subtable_or_null("probes");
  if (!table) return;
  for (const auto& [name, value] : table->as_table()) {
    if (!value.is_table())
      throw InputError(fmt::format("{}: gas.probes.{}: expected a table with at = [x, y]",
                                   origin(value, gas.file()), name));
    TableReader r(value, gas.key_path("probes." + name), gas.file());
    GasSpec::Probe p;
    p.name = name;
    r.pair("at", "the point [x, y] in m where the gas is recorded", p.at);
    if (!(p.at[0] >= g.x[0] && p.at[0] < g.x[1] && p.at[1] >= g.y[0] && p.at[1] < g.y[1]))
      r.fail("at", fmt::format("[{}, {}] is outside the gas grid [{}, {}) x [{}, {}) m", p.at[0],
                               p.at[1], g.x[0], g.x[1], g.y[0], g.y[1]));
    r.finish();
    g.probes.push_back(p);
  }
}

}  // namespace

double thinnest_width(const Shape& shape) {
  const std::vector<std::vector<Point2>> loops = outlines(shape);
  double thinnest = std::numeric_limits<double>::infinity();
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const auto& loop = loops[l];
    const double sign = l == 0 ? 1.0 : -1.0;  // holes' outlines run the same way: inward is out
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const Point2& a = loop[k];
      const Point2& b = loop[(k + 1) % loop.size()];
      const double length = std::hypot(b.x - a.x, b.y - a.y);
      if (!(length > 0)) continue;
      // The outline runs counter-clockwise: inward is the left normal.
      const Point2 inward{-sign * (b.y - a.y) / length, sign * (b.x - a.x) / length};
      const Point2 mid{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
      thinnest = std::min(thinnest, distance_to_nearest_crossing(loops, mid, inward, &a, &b));
    }
  }
  return thinnest;
}

void read_gas(TableReader& top, CaseSpec& c) {
  const TomlValue* table = top.subtable_or_null("gas");
  if (!table) return;
  if (c.dimension == 3)
    top.fail("gas", "[gas] is not available in space (dimension = 3) yet: the gas is planar");
  TableReader r(*table, "gas", top.file());
  GasSpec& g = c.gas;
  g.enabled = true;
  read_grid(r, g);
  {
    TableReader s(r.subtable("initial", "[gas.initial] with the gas's density and pressure"),
                  r.key_path("initial"), r.file());
    g.initial = read_state(s);
    s.finish();
  }
  if (const TomlValue* regions = r.subtable_or_null("regions")) {
    for (const auto& [name, value] : regions->as_table()) {
      if (!value.is_table())
        throw InputError(
            fmt::format("{}: gas.regions.{}: expected a table with a shape, "
                        "density and pressure",
                        origin(value, r.file()), name));
      TableReader s(value, r.key_path("regions." + name), r.file());
      GasSpec::Region region;
      region.name = name;
      region.shape = read_shape(s, c.source);
      region.state = read_state(s);
      s.finish();
      g.regions.push_back(region);
    }
  }
  read_shock(r, g);
  if (const TomlValue* inflow = r.subtable_or_null("inflow")) {
    TableReader s(*inflow, r.key_path("inflow"), r.file());
    g.inflow = read_state(s);
    g.inflow_given = true;
    s.finish();
  }
  const char* names[2][2] = {{"left", "right"}, {"bottom", "top"}};
  for (int a = 0; a < 2; ++a)
    for (int side = 0; side < 2; ++side)
      if (g.edges[a][side] == GasSpec::Edge::inflow && !g.inflow_given && g.mach == 0)
        r.fail(names[a][side],
               "an inflow edge needs the state it lets in: a [gas.inflow] table, or a "
               "[gas.shock] (whose shocked gas it lets in)");
  g.reference_pressure = r.number_or("reference_pressure", g.initial.pressure);
  r.range_check("reference_pressure", g.reference_pressure,
                g.reference_pressure >= 0 && std::isfinite(g.reference_pressure), "[0, inf) Pa");
  read_coupled_bodies(r, c);
  read_probes(r, g);
  r.finish();
}

}  // namespace mpsolid
