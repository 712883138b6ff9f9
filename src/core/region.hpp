#pragma once
// Regions of the plane that bodies fill with lattice sites: rectangles
// (optionally turned about their centre), circles, ellipses, annuli and
// simple polygons (concave ones too), and a body's shape as one region with
// holes cut out of it. A region answers whether a point is inside it and
// gives its bounding box and an outline, so filling, checking and drawing
// need nothing else of its kind; a third dimension adds its own regions
// (boxes, cylinders, spheres, extrusions of these) beside them.
//
// Points on a region's edge: an axis-aligned rectangle is half open,
// [x0, x1) x [y0, y1), so two rectangles that share an edge give each of
// its sites to one of them. A polygon follows the same rule, the crossing
// rule of a ray cast towards +x (an edge counts from its lower end on, up
// to its upper end; a crossing counts when it lies beyond the point): a
// point on a left or bottom edge is inside, on a right or top edge outside,
// so a rectangle written as a polygon holds the same sites and two polygons
// sharing an edge split its sites. Circles and ellipses hold the points strictly inside their
// curve; an annulus keeps its inner circle and not its outer one.
#include <cstdint>
#include <functional>
#include <string>
#include <variant>
#include <vector>

namespace mpsolid {

struct Point2 {
  double x = 0, y = 0;
  bool operator==(const Point2&) const = default;
};

struct Box2 {
  Point2 lo, hi;
};

// [x0, x1) x [y0, y1) turned by `angle_deg` (degrees, counter-clockwise:
// as the case writes it, so it reads back to the same bits) about its
// centre.
struct RectangleRegion {
  double x[2] = {0, 0}, y[2] = {0, 0};
  double angle_deg = 0;
  bool operator==(const RectangleRegion&) const = default;
};
struct CircleRegion {
  Point2 center;
  double radius = 0;
  bool operator==(const CircleRegion&) const = default;
};
// Semi-axes a along the turned x axis, b along the turned y axis.
struct EllipseRegion {
  Point2 center;
  double a = 0, b = 0;
  double angle_deg = 0;
  bool operator==(const EllipseRegion&) const = default;
};
// inner <= |p - center| < outer.
struct AnnulusRegion {
  Point2 center;
  double inner = 0, outer = 0;
  bool operator==(const AnnulusRegion&) const = default;
};
// A simple polygon (no edge crosses another), vertices in either order,
// the closing edge implied.
struct PolygonRegion {
  std::vector<Point2> vertices;
  bool operator==(const PolygonRegion&) const = default;
};

using Region =
    std::variant<RectangleRegion, CircleRegion, EllipseRegion, AnnulusRegion, PolygonRegion>;

// p turned about c by angle_deg (degrees, counter-clockwise), and back.
Point2 turn_point(Point2 p, Point2 c, double angle_deg);
Point2 unturn_point(Point2 p, Point2 c, double angle_deg);
Point2 rectangle_center(const RectangleRegion& r);

// The region's kind as the case names it ("rectangle", "circle", ...).
const char* region_kind(const Region& r);
bool region_contains(const Region& r, Point2 p);
Box2 region_bounds(const Region& r);
// The boundary as a closed polygon, counter-clockwise, first vertex not
// repeated: exact for rectangles and polygons, curves by `segments`
// vertices inscribed in them. An annulus gives its outer circle.
std::vector<Point2> region_outline(const Region& r, int segments = 256);
// Area: exact for every kind.
double region_area(const Region& r);

// A body's shape: its region less its holes.
struct Shape {
  Region region;
  std::vector<Region> holes;
  bool operator==(const Shape&) const = default;
  Box2 bounds() const { return region_bounds(region); }
};

// Whether p is in the shape: in its region and in none of its holes.
bool shape_contains(const Shape& shape, Point2 p);

// The lattice sites (centres ((k + 1/2) l0, (m + 1/2) l0)) inside the
// shape, row by row (y outer, x inner).
std::vector<Point2> fill_shape(const Shape& shape, double l0);
// The same sites one at a time, in the same order, none kept.
void visit_shape_sites(const Shape& shape, double l0, const std::function<void(Point2)>& site);
// How many there would be, without storing them.
std::int64_t count_shape_sites(const Shape& shape, double l0);
// Whether one of them lies within `distance` of p.
bool shape_has_site_near(const Shape& shape, Point2 p, double l0, double distance);

// A polygon's problems, each as a sentence, or none: fewer than 3
// vertices, a repeated vertex, zero area, and every pair of edges that cross
// or touch other than at their shared vertex ("edges 2 (from vertex 2 to 3)
// and 5 (from vertex 5 to 6) cross at (x, y)"), vertices counted from 1.
std::vector<std::string> polygon_problems(const PolygonRegion& polygon);

// Whether `inner` lies inside `outer`, and whether two shapes share area
// (holes cut out: a pin in a hole does not overlap the plate), judged on
// their outlines (curves inscribed) up to a millionth of the smaller area,
// so shapes that touch along an edge or at a point neither overlap nor
// stick out.
bool region_within(const Region& inner, const Region& outer);
bool shapes_overlap(const Shape& a, const Shape& b);

}  // namespace mpsolid
