#include "src/core/region3.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "src/core/geometry.hpp"
#include "src/core/overloaded.hpp"

namespace mpsolid {
namespace {

Point3 minus(Point3 a, Point3 b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double dot(Point3 a, Point3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Point3 cross(Point3 a, Point3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
bool in_half_open(double v, const double (&range)[2]) {
  return v >= range[0] && v < range[1];
}

bool in_holes(const Shape3& shape, Point3 p) {
  return std::any_of(shape.holes.begin(), shape.holes.end(),
                     [&](const Region3& h) { return region3_contains(h, p); });
}

// Calls site(p) for each lattice site inside the shape: an extrusion's
// layer by layer, any other's line by line along its longest extent.
template <class Site>
void for_each_site(const Shape3& shape, double l0, Site&& site) {
  if (const auto* e = std::get_if<ExtrusionRegion>(&shape.region)) {
    // Each layer is the plane shape's own fill: the same sites, the same
    // bits, as a 2D body of that section.
    const std::vector<Point2> layer = fill_shape(e->section, l0);
    const LatticeSpan kz = lattice_span(e->z[0], e->z[1], l0);
    for (std::int64_t n = kz.first - 1; n <= kz.last + 1; ++n) {
      const double z = lattice_coordinate(n, l0);
      if (!in_half_open(z, e->z)) continue;
      for (const Point2& q : layer)
        if (const Point3 p{q.x, q.y, z}; !in_holes(shape, p)) site(p);
    }
    return;
  }
  const Box3 b = shape.bounds();
  const LatticeSpan span[3] = {lattice_span(b.lo.x, b.hi.x, l0), lattice_span(b.lo.y, b.hi.y, l0),
                               lattice_span(b.lo.z, b.hi.z, l0)};
  // The lines along the longest extent (x, then y, then z where extents
  // tie), so a plate's rows are long enough for the row patterns
  // (kernels/row_patterns.hpp); then the next longest.
  int axis[3] = {0, 1, 2};  // inner, middle, outer
  const auto extent = [&](int a) { return span[a].last - span[a].first; };
  std::stable_sort(axis, axis + 3, [&](int a, int c) { return extent(a) > extent(c); });
  // One site more on each side than the box's half-open span: the region
  // decides its own surface.
  std::int64_t at[3];
  const auto from = [&](int a) { return span[axis[a]].first - 1; };
  const auto to = [&](int a) { return span[axis[a]].last + 1; };
  for (at[2] = from(2); at[2] <= to(2); ++at[2])
    for (at[1] = from(1); at[1] <= to(1); ++at[1])
      for (at[0] = from(0); at[0] <= to(0); ++at[0]) {
        std::int64_t k[3];
        for (int a = 0; a < 3; ++a) k[axis[a]] = at[a];
        const Point3 p{lattice_coordinate(k[0], l0), lattice_coordinate(k[1], l0),
                       lattice_coordinate(k[2], l0)};
        if (region3_contains(shape.region, p) && !in_holes(shape, p)) site(p);
      }
}

}  // namespace

const char* region3_kind(const Region3& r) {
  return std::visit(Overloaded{[](const BoxRegion&) { return "box"; },
                               [](const CylinderRegion&) { return "cylinder"; },
                               [](const SphereRegion&) { return "sphere"; },
                               [](const ExtrusionRegion&) { return "extrusion"; }},
                    r);
}

bool region3_contains(const Region3& r, Point3 p) {
  return std::visit(
      Overloaded{[&](const BoxRegion& b) {
                   return in_half_open(p.x, b.x) && in_half_open(p.y, b.y) &&
                          in_half_open(p.z, b.z);
                 },
                 [&](const CylinderRegion& c) {
                   const Point3 axis = minus(c.top, c.base), w = minus(p, c.base);
                   const double along = dot(w, axis), length2 = dot(axis, axis);
                   if (along < 0 || along >= length2) return false;
                   // |w x axis|^2 / |axis|^2 is the squared distance from the axis.
                   const Point3 n = cross(w, axis);
                   return dot(n, n) < c.radius * c.radius * length2;
                 },
                 [&](const SphereRegion& s) {
                   const Point3 d = minus(p, s.center);
                   return dot(d, d) < s.radius * s.radius;
                 },
                 [&](const ExtrusionRegion& e) {
                   return in_half_open(p.z, e.z) && shape_contains(e.section, {p.x, p.y});
                 }},
      r);
}

Box3 region3_bounds(const Region3& r) {
  return std::visit(
      Overloaded{[](const BoxRegion& b) {
                   return Box3{{b.x[0], b.y[0], b.z[0]}, {b.x[1], b.y[1], b.z[1]}};
                 },
                 [](const CylinderRegion& c) {
                   // Each cap's disc reaches r sqrt(1 - a_i^2) along axis i
                   // (a the unit axis).
                   const Point3 axis = minus(c.top, c.base);
                   const double length2 = dot(axis, axis);
                   const auto reach = [&](double a) {
                     return c.radius * std::sqrt(std::max(0.0, 1.0 - a * a / length2));
                   };
                   const double rx = reach(axis.x), ry = reach(axis.y), rz = reach(axis.z);
                   return Box3{{std::min(c.base.x, c.top.x) - rx, std::min(c.base.y, c.top.y) - ry,
                                std::min(c.base.z, c.top.z) - rz},
                               {std::max(c.base.x, c.top.x) + rx, std::max(c.base.y, c.top.y) + ry,
                                std::max(c.base.z, c.top.z) + rz}};
                 },
                 [](const SphereRegion& s) {
                   const Point3& c = s.center;
                   return Box3{{c.x - s.radius, c.y - s.radius, c.z - s.radius},
                               {c.x + s.radius, c.y + s.radius, c.z + s.radius}};
                 },
                 [](const ExtrusionRegion& e) {
                   const Box2 b = e.section.bounds();
                   return Box3{{b.lo.x, b.lo.y, e.z[0]}, {b.hi.x, b.hi.y, e.z[1]}};
                 }},
      r);
}

double region3_volume(const Region3& r) {
  return std::visit(
      Overloaded{[](const BoxRegion& b) {
                   return (b.x[1] - b.x[0]) * (b.y[1] - b.y[0]) * (b.z[1] - b.z[0]);
                 },
                 [](const CylinderRegion& c) {
                   const Point3 axis = minus(c.top, c.base);
                   return std::numbers::pi * c.radius * c.radius * std::sqrt(dot(axis, axis));
                 },
                 [](const SphereRegion& s) {
                   return 4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius;
                 },
                 [](const ExtrusionRegion& e) {
                   double area = region_area(e.section.region);
                   for (const Region& hole : e.section.holes) area -= region_area(hole);
                   return area * (e.z[1] - e.z[0]);
                 }},
      r);
}

bool shape3_contains(const Shape3& shape, Point3 p) {
  return region3_contains(shape.region, p) && !in_holes(shape, p);
}

std::vector<Point3> fill_shape3(const Shape3& shape, double l0) {
  std::vector<Point3> sites;
  for_each_site(shape, l0, [&](Point3 p) { sites.push_back(p); });
  return sites;
}

void visit_shape3_sites(const Shape3& shape, double l0, const std::function<void(Point3)>& site) {
  for_each_site(shape, l0, site);
}

std::int64_t count_shape3_sites(const Shape3& shape, double l0) {
  std::int64_t n = 0;
  for_each_site(shape, l0, [&](Point3) { ++n; });
  return n;
}

bool shape3_has_site_near(const Shape3& shape, Point3 p, double l0, double distance) {
  const LatticeSpan kx = lattice_span(p.x - distance, p.x + distance, l0);
  const LatticeSpan ky = lattice_span(p.y - distance, p.y + distance, l0);
  const LatticeSpan kz = lattice_span(p.z - distance, p.z + distance, l0);
  for (std::int64_t n = kz.first; n <= kz.last; ++n)
    for (std::int64_t m = ky.first; m <= ky.last; ++m)
      for (std::int64_t k = kx.first; k <= kx.last; ++k) {
        const Point3 site{lattice_coordinate(k, l0), lattice_coordinate(m, l0),
                          lattice_coordinate(n, l0)};
        const Point3 d = minus(site, p);
        if (dot(d, d) <= distance * distance && shape3_contains(shape, site)) return true;
      }
  return false;
}

bool shapes3_share_site(const Shape3& a, const Shape3& b, double l0) {
  const Box3 ba = a.bounds(), bb = b.bounds();
  if (ba.hi.x < bb.lo.x || bb.hi.x < ba.lo.x || ba.hi.y < bb.lo.y || bb.hi.y < ba.lo.y ||
      ba.hi.z < bb.lo.z || bb.hi.z < ba.lo.z)
    return false;
  bool shared = false;
  for_each_site(a, l0, [&](Point3 p) { shared = shared || shape3_contains(b, p); });
  return shared;
}

}  // namespace mpsolid
