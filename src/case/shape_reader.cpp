#include "src/case/shape_reader.hpp"

#include <fmt/format.h>

#include <cmath>

#include "src/case/pairs_file.hpp"
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

PolygonRegion read_polygon(TableReader& r, const std::string& case_file) {
  PolygonRegion polygon;
  for (const auto& [x, y] : read_pairs(r, "vertices", "vertices_file", "x, y (m)", case_file))
    polygon.vertices.push_back({x, y});
  const char* key = r.has("vertices") ? "vertices" : "vertices_file";
  const std::vector<std::string> problems = polygon_problems(polygon);
  if (!problems.empty()) {
    std::string all;
    for (const std::string& p : problems) all += (all.empty() ? "" : "; ") + p;
    r.fail(key, "not a simple polygon: " + all +
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
