#pragma once
// Regions of space that 3D bodies fill with lattice sites: boxes,
// cylinders between two points, spheres, and extrusions along z of a plane
// shape (src/core/region.hpp, holes included), and a body's 3D shape as one
// region with holes cut out of it. As in the plane, a region answers whether
// a point is inside it, its bounding box and its volume, so filling and
// checking need nothing else of its kind.
//
// Points on a region's surface: a box is half open, [x0, x1) x [y0, y1) x
// [z0, z1), so two boxes that share a face give each of its sites to one
// of them; an extrusion is half open along z and follows its section's rule
// across it, so every layer of an extrusion holds exactly the plane
// shape's sites; a cylinder holds its base's disc and not its top's, and
// the points strictly inside its curved side; a sphere the points strictly
// inside it.
#include <cstdint>
#include <functional>
#include <variant>
#include <vector>

#include "src/core/region.hpp"

namespace mpsolid {

struct Point3 {
  double x = 0, y = 0, z = 0;
  bool operator==(const Point3&) const = default;
};

struct Box3 {
  Point3 lo, hi;
};

struct BoxRegion {
  double x[2] = {0, 0}, y[2] = {0, 0}, z[2] = {0, 0};
  bool operator==(const BoxRegion&) const = default;
};
// The points within `radius` of the segment from `base` to `top`, between
// the planes through them normal to it.
struct CylinderRegion {
  Point3 base, top;
  double radius = 0;
  bool operator==(const CylinderRegion&) const = default;
};
struct SphereRegion {
  Point3 center;
  double radius = 0;
  bool operator==(const SphereRegion&) const = default;
};
// A plane shape in x-y swept along z over [z0, z1): a rod's 2D section made
// a slab, a holed plate made thick.
struct ExtrusionRegion {
  Shape section;
  double z[2] = {0, 0};
  bool operator==(const ExtrusionRegion&) const = default;
};

using Region3 = std::variant<BoxRegion, CylinderRegion, SphereRegion, ExtrusionRegion>;

// The region's kind as a case would name it ("box", "cylinder", ...).
const char* region3_kind(const Region3& r);
bool region3_contains(const Region3& r, Point3 p);
// A box holding every point of the region (tight for boxes, spheres and
// extrusions; a slanted cylinder's is its caps' discs' boxes).
Box3 region3_bounds(const Region3& r);
// Volume: exact for every kind (an extrusion's section area, holes taken
// out, times its length).
double region3_volume(const Region3& r);

// A body's 3D shape: its region less its holes.
struct Shape3 {
  Region3 region;
  std::vector<Region3> holes;
  bool operator==(const Shape3&) const = default;
  Box3 bounds() const { return region3_bounds(region); }
};

bool shape3_contains(const Shape3& shape, Point3 p);

// The lattice sites (centres ((k + 1/2) l0, (m + 1/2) l0, (n + 1/2) l0))
// inside the shape, line by line along its longest extent, then its next
// longest (x, then y, then z where extents tie: z outer, then y, x inner
// for a cube); an extrusion's layer by layer along z, each in the plane's
// order.
std::vector<Point3> fill_shape3(const Shape3& shape, double l0);
// The same sites one at a time, in the same order, none kept.
void visit_shape3_sites(const Shape3& shape, double l0, const std::function<void(Point3)>& site);
// How many there would be, without storing them.
std::int64_t count_shape3_sites(const Shape3& shape, double l0);
// Whether some lattice site of the shape lies within `distance` of p.
bool shape3_has_site_near(const Shape3& shape, Point3 p, double l0, double distance);
// Whether some lattice site of `a` lies inside `b` too (two bodies would put
// particles on one site): bodies may touch, not overlap.
bool shapes3_share_site(const Shape3& a, const Shape3& b, double l0);

}  // namespace mpsolid
