#include "src/case/shape_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "src/core/types.hpp"

namespace mpsolid {

namespace {
const std::vector<std::string> kShapes = {"rectangle", "circle", "ellipse", "annulus", "polygon"};

Point2 point(TableReader& r, const std::string& key, const std::string& what) {
  double xy[2];
  r.pair(key, what, xy);
  return {xy[0], xy[1]};
}

double positive(TableReader& r, const std::string& key, const std::string& what) {
  const double v = r.number(key, what);
  r.range_check(key, v, v > 0, "(0, inf) m");
  return v;
}

// Degrees counter-clockwise, 0 when absent.
double angle(TableReader& r) {
  const double degrees = r.number_or("angle", 0.0);
  r.range_check("angle", degrees, std::abs(degrees) <= 360, "[-360, 360] degrees");
  return degrees;
}

std::vector<Point2> inline_vertices(TableReader& r, const TomlValue& v) {
  const auto bad = [&](const std::string& problem) {
    r.fail("vertices",
           fmt::format("expected a list of [x, y] points in m ({}), got {}", problem, describe(v)));
  };
  if (!v.is_array()) bad("not a list");
  std::vector<Point2> out;
  for (const TomlValue& item : v.as_array()) {
    if (!item.is_array() || item.as_array().size() != 2) bad("each vertex is two numbers");
    out.push_back({r.number(item.as_array()[0], "vertices", "a vertex's x in m"),
                   r.number(item.as_array()[1], "vertices", "a vertex's y in m")});
  }
  return out;
}

PolygonRegion read_polygon(TableReader& r, const std::string& case_file) {
  const TomlValue* inline_list = r.find("vertices");
  const TomlValue* file = r.find("vertices_file");
  if ((inline_list != nullptr) == (file != nullptr))
    r.fail(inline_list ? "vertices" : "vertices_file",
           "a polygon takes either vertices = [[x, y], ...] or vertices_file = \"FILE.csv\"");
  PolygonRegion polygon;
  if (inline_list) {
    polygon.vertices = inline_vertices(r, *inline_list);
  } else {
    const std::string name = r.string("vertices_file", "a CSV file of x, y lines");
    std::filesystem::path path(name);
    if (path.is_relative()) path = std::filesystem::path(case_file).parent_path() / path;
    polygon.vertices = read_vertices_file(path.string(), r.key_path("vertices_file"));
  }
  const std::vector<std::string> problems = polygon_problems(polygon);
  if (!problems.empty()) {
    std::string all;
    for (const std::string& p : problems) all += (all.empty() ? "" : "; ") + p;
    r.fail(inline_list ? "vertices" : "vertices_file",
           "not a simple polygon: " + all +
               " (a polygon's edges may meet only at their shared "
               "vertices)");
  }
  return polygon;
}

// One region from a table: its shape key and that shape's keys.
Region read_region(TableReader& r, const std::string& case_file) {
  const std::string kind = r.choice_or("shape", kShapes, "rectangle");
  if (kind == "rectangle") {
    RectangleRegion rect;
    r.pair("x", "the rectangle's x range [x0, x1] in m", rect.x);
    r.pair("y", "the rectangle's y range [y0, y1] in m", rect.y);
    if (!(rect.x[0] < rect.x[1]))
      r.fail("x", fmt::format("needs x0 < x1, got [{}, {}]", rect.x[0], rect.x[1]));
    if (!(rect.y[0] < rect.y[1]))
      r.fail("y", fmt::format("needs y0 < y1, got [{}, {}]", rect.y[0], rect.y[1]));
    rect.angle_deg = angle(r);
    return rect;
  }
  if (kind == "circle") {
    CircleRegion c;
    c.center = point(r, "center", "the centre [x, y] in m");
    c.radius = positive(r, "radius", "the radius in m");
    return c;
  }
  if (kind == "ellipse") {
    EllipseRegion e;
    e.center = point(r, "center", "the centre [x, y] in m");
    double ab[2];
    r.pair("semi_axes", "the semi-axes [a, b] in m, a along the turned x axis", ab);
    r.range_check("semi_axes", std::min(ab[0], ab[1]), ab[0] > 0 && ab[1] > 0, "(0, inf) m each");
    e.a = ab[0];
    e.b = ab[1];
    e.angle_deg = angle(r);
    return e;
  }
  if (kind == "annulus") {
    AnnulusRegion a;
    a.center = point(r, "center", "the centre [x, y] in m");
    double radii[2];
    r.pair("radii", "the radii [inner, outer] in m", radii);
    if (!(radii[0] > 0 && radii[0] < radii[1]))
      r.fail("radii", fmt::format("needs 0 < inner < outer, got [{}, {}]", radii[0], radii[1]));
    a.inner = radii[0];
    a.outer = radii[1];
    return a;
  }
  return read_polygon(r, case_file);
}
}  // namespace

std::vector<Point2> read_vertices_file(const std::string& path, const std::string& key_path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(fmt::format("{}: {}: cannot read the vertex file (a CSV file of x, y lines)",
                                 path, key_path));
  std::vector<Point2> vertices;
  std::string line;
  bool header_allowed = true;
  for (int number = 1; std::getline(in, line); ++number) {
    std::string text = line;
    for (char& ch : text)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    const auto first = text.find_first_not_of(' ');
    if (first == std::string::npos || text[first] == '#') continue;
    std::istringstream fields(text);
    double x = 0, y = 0;
    std::string rest;
    const bool two = static_cast<bool>(fields >> x >> y) && !(fields >> rest);
    if (!two || !std::isfinite(x) || !std::isfinite(y)) {
      // One line of column names may come first.
      if (header_allowed && std::isalpha(static_cast<unsigned char>(text[first]))) {
        header_allowed = false;
        continue;
      }
      throw InputError(fmt::format("{}:{}: {}: expected two finite numbers x, y (m), got '{}'",
                                   path, number, key_path, line));
    }
    header_allowed = false;
    vertices.push_back({x, y});
  }
  if (vertices.empty())
    throw InputError(fmt::format("{}: {}: no vertices in the file", path, key_path));
  return vertices;
}

Shape read_shape(TableReader& r, const std::string& case_file) {
  Shape shape;
  shape.region = read_region(r, case_file);
  const TomlValue* holes = r.find("holes");
  if (!holes) return shape;
  if (!holes->is_array())
    r.fail("holes",
           "expected a list of regions, e.g. holes = [{ shape = \"circle\", center = "
           "[x, y], radius = r }]");
  for (std::size_t k = 0; k < holes->as_array().size(); ++k) {
    const TomlValue& table = holes->as_array()[k];
    const std::string path = r.key_path("holes") + fmt::format("[{}]", k);
    if (!table.is_table())
      r.fail("holes", fmt::format("hole {} is not a table with a shape and its keys", k + 1));
    TableReader h(table, path, r.file());
    const Region hole = read_region(h, case_file);
    h.finish();
    if (!region_within(hole, shape.region))
      h.fail("shape", fmt::format("the hole ({}) is not inside the body's {}", region_kind(hole),
                                  region_kind(shape.region)));
    shape.holes.push_back(hole);
  }
  return shape;
}

}  // namespace mpsolid
