#include "src/core/region.hpp"

// Boost.Geometry's rescaling policy trips GCC's maybe-uninitialized analysis
// when its set operations are inlined here (a known false positive).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// Boost 1.74's math constants include a header it has since deprecated; the
// note it prints on every build says nothing about this code.
#define BOOST_ALLOW_DEPRECATED_HEADERS

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <cmath>
#include <numbers>
#include <sstream>

#include "src/core/geometry.hpp"
#include "src/core/overloaded.hpp"
#include "src/core/region_boundary.hpp"

namespace mpsolid {

namespace bg = boost::geometry;

namespace {
using BgPoint = bg::model::d2::point_xy<double>;
using BgPolygon = bg::model::polygon<BgPoint, false>;  // counter-clockwise, closed
using BgMulti = bg::model::multi_polygon<BgPolygon>;
using BgSegment = bg::model::segment<BgPoint>;

double radians(double degrees) {
  return degrees * (std::numbers::pi / 180.0);
}

BgPolygon to_bg(const std::vector<Point2>& outline) {
  BgPolygon poly;
  for (const Point2& v : outline) poly.outer().emplace_back(v.x, v.y);
  bg::correct(poly);  // closes the ring and orders it counter-clockwise
  return poly;
}

// The crossing rule: a ray from p towards +x crosses edge (a, b) when the
// edge spans p.y counting from its lower end on, at an x beyond p.x. The
// crossing's x is computed from the edge's lower end whichever way the
// polygon runs, so two polygons sharing an edge compute the same x for a
// site on it and exactly one of them holds it. (Boost.Geometry's
// point-in-polygon strategies compute an edge's side from its direction,
// which does not split a shared slanted edge's sites exactly; it does the
// rest: validity, areas, containment, overlap.)
// Calls crossing(x) for each edge the ray at height y crosses.
template <class Crossing>
void for_each_crossing(const std::vector<Point2>& v, double y, Crossing&& crossing) {
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
    const Point2 a = v[j].y < v[i].y ? v[j] : v[i], b = v[j].y < v[i].y ? v[i] : v[j];
    if (a.y <= y && y < b.y) crossing(a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y));
  }
}

bool polygon_contains(const PolygonRegion& r, Point2 p) {
  bool inside = false;
  for_each_crossing(r.vertices, p.y, [&](double x) { inside = inside != (p.x < x); });
  return inside;
}

// Twice the signed area (positive counter-clockwise).
double signed_area2(const std::vector<Point2>& v) {
  double sum = 0;
  for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
    sum += (v[j].x - v[i].x) * (v[j].y + v[i].y);
  return sum;
}

std::vector<Point2> ellipse_outline(Point2 c, double a, double b, double angle_deg, int segments) {
  std::vector<Point2> out;
  for (int k = 0; k < segments; ++k) {
    const double t = 2.0 * std::numbers::pi * k / segments;
    out.push_back(turn_point({c.x + a * std::cos(t), c.y + b * std::sin(t)}, c, angle_deg));
  }
  return out;
}

BgMulti shape_area(const Shape& s) {
  BgMulti body;
  body.push_back(to_bg(region_outline(s.region)));
  for (const Region& hole : s.holes) {
    BgMulti rest;
    bg::difference(body, to_bg(region_outline(hole)), rest);
    body = std::move(rest);
  }
  return body;
}
}  // namespace

Point2 unturn_point(Point2 p, Point2 c, double angle_deg) {
  const double angle = radians(angle_deg);
  const double cs = std::cos(angle), sn = std::sin(angle);
  const double dx = p.x - c.x, dy = p.y - c.y;
  return {c.x + cs * dx + sn * dy, c.y - sn * dx + cs * dy};
}
Point2 turn_point(Point2 p, Point2 c, double angle_deg) {
  return unturn_point(p, c, -angle_deg);
}

Point2 rectangle_center(const RectangleRegion& r) {
  return {0.5 * (r.x[0] + r.x[1]), 0.5 * (r.y[0] + r.y[1])};
}

const char* region_kind(const Region& r) {
  return std::visit(Overloaded{[](const RectangleRegion&) { return "rectangle"; },
                               [](const CircleRegion&) { return "circle"; },
                               [](const EllipseRegion&) { return "ellipse"; },
                               [](const AnnulusRegion&) { return "annulus"; },
                               [](const PolygonRegion&) { return "polygon"; }},
                    r);
}

bool region_contains(const Region& region, Point2 p) {
  return std::visit(
      Overloaded{[&](const RectangleRegion& r) {
                   // Half open, turned about the centre when it has an angle.
                   const Point2 q =
                       r.angle_deg == 0 ? p : unturn_point(p, rectangle_center(r), r.angle_deg);
                   return q.x >= r.x[0] && q.x < r.x[1] && q.y >= r.y[0] && q.y < r.y[1];
                 },
                 [&](const CircleRegion& r) {
                   const double dx = p.x - r.center.x, dy = p.y - r.center.y;
                   return dx * dx + dy * dy < r.radius * r.radius;
                 },
                 [&](const EllipseRegion& r) {
                   const Point2 q = unturn_point(p, r.center, r.angle_deg);
                   const double u = (q.x - r.center.x) / r.a, v = (q.y - r.center.y) / r.b;
                   return u * u + v * v < 1.0;
                 },
                 [&](const AnnulusRegion& r) {
                   const double dx = p.x - r.center.x, dy = p.y - r.center.y;
                   const double d2 = dx * dx + dy * dy;
                   return d2 >= r.inner * r.inner && d2 < r.outer * r.outer;
                 },
                 [&](const PolygonRegion& r) { return polygon_contains(r, p); }},
      region);
}

bool shape_contains(const Shape& shape, Point2 p) {
  if (!region_contains(shape.region, p)) return false;
  return std::none_of(shape.holes.begin(), shape.holes.end(),
                      [&](const Region& hole) { return region_contains(hole, p); });
}

Box2 region_bounds(const Region& region) {
  return std::visit(
      Overloaded{
          [](const RectangleRegion& r) {
            if (r.angle_deg == 0) return Box2{{r.x[0], r.y[0]}, {r.x[1], r.y[1]}};
            return region_bounds(PolygonRegion{region_outline(r)});
          },
          [](const CircleRegion& r) {
            return Box2{{r.center.x - r.radius, r.center.y - r.radius},
                        {r.center.x + r.radius, r.center.y + r.radius}};
          },
          [](const EllipseRegion& r) {
            // The extent of a turned ellipse along x and y.
            const double c = std::cos(radians(r.angle_deg)), s = std::sin(radians(r.angle_deg));
            const double hx = std::hypot(r.a * c, r.b * s);
            const double hy = std::hypot(r.a * s, r.b * c);
            return Box2{{r.center.x - hx, r.center.y - hy}, {r.center.x + hx, r.center.y + hy}};
          },
          [](const AnnulusRegion& r) {
            return Box2{{r.center.x - r.outer, r.center.y - r.outer},
                        {r.center.x + r.outer, r.center.y + r.outer}};
          },
          [](const PolygonRegion& r) {
            Box2 b{r.vertices.at(0), r.vertices.at(0)};
            for (const Point2& v : r.vertices) {
              b.lo.x = std::min(b.lo.x, v.x);
              b.lo.y = std::min(b.lo.y, v.y);
              b.hi.x = std::max(b.hi.x, v.x);
              b.hi.y = std::max(b.hi.y, v.y);
            }
            return b;
          }},
      region);
}

std::vector<Point2> region_outline(const Region& region, int segments) {
  return std::visit(
      Overloaded{[](const RectangleRegion& r) {
                   const Point2 c = rectangle_center(r);
                   std::vector<Point2> out;
                   for (const Point2 v : {Point2{r.x[0], r.y[0]}, Point2{r.x[1], r.y[0]},
                                          Point2{r.x[1], r.y[1]}, Point2{r.x[0], r.y[1]}})
                     out.push_back(r.angle_deg == 0 ? v : turn_point(v, c, r.angle_deg));
                   return out;
                 },
                 [&](const CircleRegion& r) {
                   return ellipse_outline(r.center, r.radius, r.radius, 0, segments);
                 },
                 [&](const EllipseRegion& r) {
                   return ellipse_outline(r.center, r.a, r.b, r.angle_deg, segments);
                 },
                 [&](const AnnulusRegion& r) {
                   return ellipse_outline(r.center, r.outer, r.outer, 0, segments);
                 },
                 [](const PolygonRegion& r) {
                   std::vector<Point2> out = r.vertices;
                   if (signed_area2(out) < 0) std::reverse(out.begin(), out.end());
                   return out;
                 }},
      region);
}

double region_area(const Region& region) {
  return std::visit(
      Overloaded{[](const RectangleRegion& r) { return (r.x[1] - r.x[0]) * (r.y[1] - r.y[0]); },
                 [](const CircleRegion& r) { return std::numbers::pi * r.radius * r.radius; },
                 [](const EllipseRegion& r) { return std::numbers::pi * r.a * r.b; },
                 [](const AnnulusRegion& r) {
                   return std::numbers::pi * (r.outer * r.outer - r.inner * r.inner);
                 },
                 [](const PolygonRegion& r) { return bg::area(to_bg(r.vertices)); }},
      region);
}

namespace {
// A shape's test of lattice sites. An unturned rectangle holds the sites of
// its half-open lattice spans, with lattice_span's slack for decimal round-off in the
// case file, whether it is a body or a hole.
class ShapeTest {
 public:
  ShapeTest(const Shape& shape, double l0) : shape_(shape), l0_(l0) {
    add(shape.region);
    for (const Region& hole : shape.holes) add(hole);
  }
  bool contains(std::int64_t k, std::int64_t m) {
    const Point2 p{lattice_coordinate(k, l0_), lattice_coordinate(m, l0_)};
    if (!inside(0, k, m, p)) return false;
    for (std::size_t h = 1; h < tests_.size(); ++h)
      if (inside(h, k, m, p)) return false;
    return true;
  }

 private:
  struct Test {
    LatticeSpan kx, ky;  // an unturned rectangle's
    bool spans = false;
    // A polygon's crossings with the row `row`, sorted: a site is inside
    // when an odd number lie beyond it (polygon_contains, row by row).
    std::int64_t row = 0;
    std::vector<double> crossings;
    bool has_row = false;
  };
  void add(const Region& r) {
    Test t;
    if (const auto* rect = std::get_if<RectangleRegion>(&r); rect && rect->angle_deg == 0) {
      t.kx = lattice_span(rect->x[0], rect->x[1], l0_);
      t.ky = lattice_span(rect->y[0], rect->y[1], l0_);
      t.spans = true;
    }
    tests_.push_back(t);
  }
  bool inside(std::size_t h, std::int64_t k, std::int64_t m, Point2 p) {
    Test& t = tests_[h];
    if (t.spans) return k >= t.kx.first && k <= t.kx.last && m >= t.ky.first && m <= t.ky.last;
    const Region& r = h == 0 ? shape_.region : shape_.holes[h - 1];
    const auto* polygon = std::get_if<PolygonRegion>(&r);
    if (!polygon) return region_contains(r, p);
    if (!t.has_row || t.row != m) {
      t.crossings.clear();
      for_each_crossing(polygon->vertices, p.y, [&](double x) { t.crossings.push_back(x); });
      std::sort(t.crossings.begin(), t.crossings.end());
      t.row = m;
      t.has_row = true;
    }
    const auto beyond =
        t.crossings.end() - std::upper_bound(t.crossings.begin(), t.crossings.end(), p.x);
    return beyond % 2 == 1;
  }
  const Shape& shape_;
  double l0_;
  std::vector<Test> tests_;  // the region first, then the holes
};

// Calls site(x, y) for each lattice site inside the shape, row by row.
template <class Site>
void for_each_site(const Shape& shape, double l0, Site&& site) {
  const Box2 b = shape.bounds();
  const LatticeSpan kx = lattice_span(b.lo.x, b.hi.x, l0), ky = lattice_span(b.lo.y, b.hi.y, l0);
  // One site more on each side than the box's half-open span: the region
  // decides its own edges.
  ShapeTest test(shape, l0);
  for (std::int64_t m = ky.first - 1; m <= ky.last + 1; ++m)
    for (std::int64_t k = kx.first - 1; k <= kx.last + 1; ++k)
      if (test.contains(k, m)) site(lattice_coordinate(k, l0), lattice_coordinate(m, l0));
}
}  // namespace

std::vector<Point2> fill_shape(const Shape& shape, double l0) {
  std::vector<Point2> sites;
  for_each_site(shape, l0, [&](double x, double y) { sites.push_back({x, y}); });
  return sites;
}

void visit_shape_sites(const Shape& shape, double l0, const std::function<void(Point2)>& site) {
  for_each_site(shape, l0, [&](double x, double y) { site({x, y}); });
}

std::int64_t count_shape_sites(const Shape& shape, double l0) {
  std::int64_t n = 0;
  for_each_site(shape, l0, [&](double, double) { ++n; });
  return n;
}

bool shape_has_site_near(const Shape& shape, Point2 p, double l0, double distance) {
  const LatticeSpan kx = lattice_span(p.x - distance, p.x + distance, l0);
  const LatticeSpan ky = lattice_span(p.y - distance, p.y + distance, l0);
  ShapeTest test(shape, l0);
  for (std::int64_t m = ky.first; m <= ky.last; ++m)
    for (std::int64_t k = kx.first; k <= kx.last; ++k) {
      const double dx = lattice_coordinate(k, l0) - p.x, dy = lattice_coordinate(m, l0) - p.y;
      if (dx * dx + dy * dy <= distance * distance && test.contains(k, m)) return true;
    }
  return false;
}

std::vector<std::string> polygon_problems(const PolygonRegion& polygon) {
  std::vector<std::string> problems;
  const std::vector<Point2>& v = polygon.vertices;
  const std::size_t n = v.size();
  if (n < 3) {
    problems.push_back("a polygon needs at least 3 vertices, got " + std::to_string(n));
    return problems;
  }
  const auto number = [](double x) {
    std::ostringstream out;
    out.precision(10);
    out << x;
    return out.str();
  };
  const auto at = [&](Point2 p) { return "(" + number(p.x) + ", " + number(p.y) + ")"; };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (v[i].x == v[j].x && v[i].y == v[j].y)
        problems.push_back("vertices " + std::to_string(i + 1) + " and " + std::to_string(j + 1) +
                           " are the same point " + at(v[i]));
  if (!problems.empty()) return problems;
  bool collinear = true;
  for (std::size_t i = 2; i < n; ++i)
    collinear =
        collinear && (v[1].x - v[0].x) * (v[i].y - v[0].y) == (v[1].y - v[0].y) * (v[i].x - v[0].x);
  if (collinear) {
    problems.push_back("the polygon has no area (its vertices lie on one line)");
    return problems;
  }
  const auto edge = [&](std::size_t i) {
    return BgSegment(BgPoint(v[i].x, v[i].y), BgPoint(v[(i + 1) % n].x, v[(i + 1) % n].y));
  };
  const auto name = [&](std::size_t i) {
    return std::to_string(i + 1) + " (from vertex " + std::to_string(i + 1) + " to " +
           std::to_string((i + 1) % n + 1) + ")";
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      std::vector<BgPoint> meet;
      bg::intersection(edge(i), edge(j), meet);
      // Adjacent edges meet at their shared vertex (one point, which Boost
      // may round off it), or overlap along a stretch (two points).
      if (adjacent ? meet.size() > 1 : !meet.empty())
        problems.push_back("edges " + name(i) + " and " + name(j) +
                           (adjacent ? " fold back along each other from " : " cross at ") +
                           at({meet.front().x(), meet.front().y()}));
    }
  return problems;
}

bool region_within(const Region& inner, const Region& outer) {
  const BgPolygon a = to_bg(region_outline(inner)), b = to_bg(region_outline(outer));
  BgMulti outside;
  bg::difference(a, b, outside);
  return bg::area(outside) <= 1e-6 * bg::area(a);
}

bool shapes_overlap(const Shape& a, const Shape& b) {
  const BgMulti pa = shape_area(a), pb = shape_area(b);
  BgMulti both;
  bg::intersection(pa, pb, both);
  return bg::area(both) > 1e-6 * std::min(bg::area(pa), bg::area(pb));
}

}  // namespace mpsolid

namespace mpsolid {

std::string boundary_problem(const Shape& shape) {
  struct Ring {
    std::string name;
    bg::model::linestring<BgPoint> line;
    BgPolygon area;
    bool hole;
  };
  std::vector<Ring> rings;
  const auto add_ring = [&](const std::vector<Point2>& outline, std::string name, bool hole) {
    Ring ring{std::move(name), {}, to_bg(outline), hole};
    for (const Point2& v : outline) ring.line.emplace_back(v.x, v.y);
    ring.line.push_back(ring.line.front());
    rings.push_back(std::move(ring));
  };
  const auto add = [&](const Region& r, const std::string& name, bool hole) {
    add_ring(region_outline(r), name, hole);
    if (const auto* annulus = std::get_if<AnnulusRegion>(&r))
      add_ring(region_outline(CircleRegion{annulus->center, annulus->inner}),
               name + "'s inner circle", hole);
  };
  add(shape.region, "the body's edge", false);
  for (std::size_t k = 0; k < shape.holes.size(); ++k)
    add(shape.holes[k], "hole " + std::to_string(k + 1), true);
  for (std::size_t a = 0; a < rings.size(); ++a)
    for (std::size_t b = a + 1; b < rings.size(); ++b) {
      if (bg::intersects(rings[a].line, rings[b].line))
        return rings[a].name + " and " + rings[b].name + " touch";
      if (!rings[a].hole || !rings[b].hole) continue;
      if (bg::within(rings[a].line.front(), rings[b].area))
        return rings[a].name + " lies inside " + rings[b].name;
      if (bg::within(rings[b].line.front(), rings[a].area))
        return rings[b].name + " lies inside " + rings[a].name;
    }
  return "";
}

}  // namespace mpsolid
