#include "src/core/region3_boundary.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "src/core/overloaded.hpp"
#include "src/core/region_boundary.hpp"

namespace mpsolid {
namespace {
using Vec = Eigen::Vector3d;

Vec vec(Point3 p) {
  return {p.x, p.y, p.z};
}
Point3 point(const Vec& v) {
  return {v.x(), v.y(), v.z()};
}

// Keeps the nearer of the candidates offered.
class Nearest {
 public:
  explicit Nearest(Point3 p) : p_(vec(p)) {}
  void offer(const Vec& at, int face) {
    const double d = (at - p_).norm();
    if (d < best_.distance) best_ = {point(at), face, d};
  }
  SurfacePoint3 best() const { return best_; }

 private:
  Vec p_;
  SurfacePoint3 best_{{}, -1, std::numeric_limits<double>::infinity()};
};

// A section's named faces: a rectangle's four, a polygon's edges, else none.
int section_faces(const Shape& section) {
  if (std::holds_alternative<RectangleRegion>(section.region)) return 4;
  if (const auto* polygon = std::get_if<PolygonRegion>(&section.region))
    return static_cast<int>(polygon->vertices.size());
  return 0;
}

void offer_box(const BoxRegion& b, Point3 p, Nearest& nearest) {
  const double lo[3] = {b.x[0], b.y[0], b.z[0]}, hi[3] = {b.x[1], b.y[1], b.z[1]};
  const Vec q = vec(p);
  Vec clamped;
  for (int a = 0; a < 3; ++a) clamped[a] = std::clamp(q[a], lo[a], hi[a]);
  // Each face's plane, the point clamped into the box then onto it.
  constexpr int kAxis[6] = {1, 0, 1, 0, 2, 2};
  constexpr bool kHigh[6] = {false, true, true, false, false, true};
  for (int face = 0; face < 6; ++face) {
    Vec on = clamped;
    on[kAxis[face]] = kHigh[face] ? hi[kAxis[face]] : lo[kAxis[face]];
    nearest.offer(on, face);
  }
}

void offer_cylinder(const CylinderRegion& c, Point3 p, Nearest& nearest) {
  const Vec base = vec(c.base), axis = vec(c.top) - base;
  const double length = axis.norm();
  const Vec u = axis / length, w = vec(p) - base;
  const double along = w.dot(u);
  Vec radial = w - along * u;
  const double rho = radial.norm();
  // On the axis every direction across it is as near: take one.
  const Vec e = rho > 0 ? Vec(radial / rho) : u.unitOrthogonal();
  nearest.offer(base + std::clamp(along, 0.0, length) * u + c.radius * e, 0);
  const Vec across = std::min(rho, c.radius) * e;
  nearest.offer(base + across, 1);
  nearest.offer(base + length * u + across, 2);
}

void offer_sphere(const SphereRegion& s, Point3 p, Nearest& nearest) {
  const Vec d = vec(p) - vec(s.center);
  const double r = d.norm();
  nearest.offer(vec(s.center) + s.radius * (r > 0 ? Vec(d / r) : Vec::UnitX()), -1);
}

void offer_extrusion(const ExtrusionRegion& e, Point3 p, Nearest& nearest) {
  const Point2 q{p.x, p.y};
  const double z = std::clamp(p.z, e.z[0], e.z[1]);
  for (const BoundaryLoop& loop : shape_boundary(e.section))
    for (const BoundaryPiece& piece : loop) {
      const Point2 on = piece_point(piece, piece_parameter(piece, q));
      nearest.offer({on.x, on.y, z}, piece.face);
    }
  // Over the section the caps are nearer than the rim (offered above).
  if (shape_contains(e.section, q)) {
    const int back = section_faces(e.section);
    nearest.offer({p.x, p.y, e.z[0]}, back);
    nearest.offer({p.x, p.y, e.z[1]}, back + 1);
  }
}

void offer_region(const Region3& r, Point3 p, Nearest& nearest) {
  std::visit(Overloaded{[&](const BoxRegion& b) { offer_box(b, p, nearest); },
                        [&](const CylinderRegion& c) { offer_cylinder(c, p, nearest); },
                        [&](const SphereRegion& s) { offer_sphere(s, p, nearest); },
                        [&](const ExtrusionRegion& e) { offer_extrusion(e, p, nearest); }},
             r);
}

// Whether q lies inside r farther than `slack` from its surface.
bool deep_inside(const Region3& r, Point3 q, double slack) {
  return region3_contains(r, q) && nearest_region3_surface_point(r, q).distance > slack;
}
}  // namespace

SurfacePoint3 nearest_region3_surface_point(const Region3& r, Point3 p) {
  Nearest nearest(p);
  offer_region(r, p, nearest);
  return nearest.best();
}

SurfacePoint3 nearest_shape3_surface_point(const Shape3& shape, Point3 p) {
  if (shape.holes.empty()) return nearest_region3_surface_point(shape.region, p);
  // Round-off from the surface counts as on it.
  const Box3 b = shape.bounds();
  const double slack = 1e-9 * std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z});
  const auto in_a_hole = [&](Point3 q, std::size_t skip) {
    for (std::size_t h = 0; h < shape.holes.size(); ++h)
      if (h != skip && deep_inside(shape.holes[h], q, slack)) return true;
    return false;
  };
  SurfacePoint3 best{{}, -1, std::numeric_limits<double>::infinity()};
  const auto keep = [&](const SurfacePoint3& c) {
    if (c.distance < best.distance) best = c;
  };
  if (const SurfacePoint3 c = nearest_region3_surface_point(shape.region, p);
      !in_a_hole(c.at, shape.holes.size()))
    keep(c);
  for (std::size_t h = 0; h < shape.holes.size(); ++h) {
    SurfacePoint3 c = nearest_region3_surface_point(shape.holes[h], p);
    c.face = -1;
    const bool in_region = region3_contains(shape.region, c.at) ||
                           nearest_region3_surface_point(shape.region, c.at).distance <= slack;
    if (in_region && !in_a_hole(c.at, h)) keep(c);
  }
  // Where a hole meets the region's surface the nearest point can fall in
  // neither set as tested; the region's then stands.
  return std::isfinite(best.distance) ? best : nearest_region3_surface_point(shape.region, p);
}

std::vector<std::string> region3_face_names(const Region3& r) {
  return std::visit(
      Overloaded{[](const BoxRegion&) {
                   return std::vector<std::string>{"bottom", "right", "top",
                                                   "left",   "back",  "front"};
                 },
                 [](const CylinderRegion&) {
                   return std::vector<std::string>{"side", "base", "top"};
                 },
                 [](const SphereRegion&) { return std::vector<std::string>{}; },
                 [](const ExtrusionRegion& e) {
                   std::vector<std::string> names;
                   const int faces = section_faces(e.section);
                   for (int k = 0; k < faces; ++k)
                     names.push_back(std::holds_alternative<RectangleRegion>(e.section.region)
                                         ? std::string(kRectangleFaces[k])
                                         : std::to_string(k + 1));
                   names.push_back("back");
                   names.push_back("front");
                   return names;
                 }},
      r);
}

}  // namespace mpsolid
