#include "src/case/shape_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "src/case/pairs_file.hpp"
#include "src/core/types.hpp"

namespace mpsolid {

namespace {
const std::vector<std::string> kShapes = {"rectangle", "circle", "ellipse", "annulus", "polygon"};
const std::vector<std::string> kShapes3 = {"box", "cylinder", "sphere", "extrusion"};

// [lo, hi] with lo < hi.
void range(TableReader& r, const std::string& key, const std::string& what, double out[2]) {
  r.pair(key, what, out);
  if (!(out[0] < out[1]))
    r.fail(key, fmt::format("needs {0}0 < {0}1, got [{1}, {2}]", key, out[0], out[1]));
}

Point3 point3(TableReader& r, const std::string& key, const std::string& what) {
  double xyz[3];
  r.numbers(key, what, xyz, 3);
  return {xyz[0], xyz[1], xyz[2]};
}

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
    range(r, "x", "the rectangle's x range [x0, x1] in m", rect.x);
    range(r, "y", "the rectangle's y range [y0, y1] in m", rect.y);
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
// A region of space from a table: its shape key and that shape's keys.
Region3 read_region3(TableReader& r, const std::string& case_file) {
  const TomlValue* kind_value = r.find("shape");
  if (kind_value && kind_value->is_string() &&
      std::find(kShapes.begin(), kShapes.end(), kind_value->as_string().str) != kShapes.end())
    r.fail("shape", fmt::format("'{}' is a plane shape; in space (dimension = 3) a body is a box, "
                                "cylinder, sphere or extrusion (a plane shape swept along z: "
                                "shape = \"extrusion\", section = {{ shape = \"{}\", ... }}, "
                                "z = [z0, z1])",
                                kind_value->as_string().str, kind_value->as_string().str));
  const std::string kind = r.choice_or("shape", kShapes3, "box");
  if (kind == "box") {
    BoxRegion box;
    range(r, "x", "the box's x range [x0, x1] in m", box.x);
    range(r, "y", "the box's y range [y0, y1] in m", box.y);
    range(r, "z", "the box's z range [z0, z1] in m", box.z);
    return box;
  }
  if (kind == "cylinder") {
    CylinderRegion c;
    c.base = point3(r, "base", "the centre [x, y, z] of the base in m");
    c.top = point3(r, "top", "the centre [x, y, z] of the top in m");
    if (c.base == c.top) r.fail("top", "the top is the base: a cylinder needs a length");
    c.radius = positive(r, "radius", "the radius in m");
    return c;
  }
  if (kind == "sphere") {
    SphereRegion sphere;
    sphere.center = point3(r, "center", "the centre [x, y, z] in m");
    sphere.radius = positive(r, "radius", "the radius in m");
    return sphere;
  }
  ExtrusionRegion e;
  const TomlValue& section =
      r.subtable("section", "the plane shape swept along z, e.g. { shape = \"circle\", ... }");
  TableReader s(section, r.key_path("section"), r.file());
  e.section = read_shape(s, case_file);
  s.finish();
  range(r, "z", "the extrusion's z range [z0, z1] in m", e.z);
  return e;
}

bool boxes_meet(const Box3& a, const Box3& b) {
  return a.lo.x < b.hi.x && b.lo.x < a.hi.x && a.lo.y < b.hi.y && b.lo.y < a.hi.y &&
         a.lo.z < b.hi.z && b.lo.z < a.hi.z;
}

// Calls each(reader, path) for each table of a `holes` list.
template <class Each>
void for_each_hole(TableReader& r, Each&& each) {
  const TomlValue* holes = r.find("holes");
  if (!holes) return;
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
    each(h);
    h.finish();
  }
}
}  // namespace

Shape3 read_shape3(TableReader& r, const std::string& case_file) {
  Shape3 shape;
  shape.region = read_region3(r, case_file);
  for_each_hole(r, [&](TableReader& h) {
    const Region3 hole = read_region3(h, case_file);
    // A hole may cut a notch through the surface, but one that misses the
    // body is a typo.
    if (!boxes_meet(region3_bounds(hole), shape.bounds()))
      h.fail("shape", fmt::format("the hole ({}) does not meet the body's {}", region3_kind(hole),
                                  region3_kind(shape.region)));
    shape.holes.push_back(hole);
  });
  return shape;
}

Shape read_shape(TableReader& r, const std::string& case_file) {
  Shape shape;
  shape.region = read_region(r, case_file);
  for_each_hole(r, [&](TableReader& h) {
    const Region hole = read_region(h, case_file);
    if (!region_within(hole, shape.region))
      h.fail("shape", fmt::format("the hole ({}) is not inside the body's {}", region_kind(hole),
                                  region_kind(shape.region)));
    shape.holes.push_back(hole);
  });
  return shape;
}

}  // namespace mpsolid
