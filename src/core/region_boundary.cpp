#include "src/core/region_boundary.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

namespace mpsolid {

namespace {
BoundaryPiece edge(Point2 a, Point2 b, int face) {
  BoundaryPiece piece;
  piece.a = a;
  piece.b = b;
  piece.face = face;
  return piece;
}

BoundaryPiece ellipse(Point2 center, double ra, double rb, double angle_deg) {
  BoundaryPiece piece;
  piece.kind = BoundaryPiece::Kind::ellipse;
  piece.center = center;
  piece.ra = ra;
  piece.rb = rb;
  piece.angle_deg = angle_deg;
  return piece;
}

// The same loop run the other way: a hole's.
BoundaryLoop reversed(BoundaryLoop loop) {
  std::reverse(loop.begin(), loop.end());
  for (BoundaryPiece& piece : loop) {
    std::swap(piece.a, piece.b);
    piece.counter_clockwise = !piece.counter_clockwise;
    piece.face = -1;
  }
  return loop;
}

// The region's loops, counter-clockwise (an annulus's inner circle clockwise).
std::vector<BoundaryLoop> region_loops(const Region& region) {
  if (const auto* r = std::get_if<RectangleRegion>(&region)) {
    const std::vector<Point2> c = region_outline(*r);  // counter-clockwise from (x0, y0)
    BoundaryLoop loop;
    for (int k = 0; k < 4; ++k) loop.push_back(edge(c[k], c[(k + 1) % 4], k));
    return {loop};
  }
  if (const auto* r = std::get_if<CircleRegion>(&region))
    return {{ellipse(r->center, r->radius, r->radius, 0)}};
  if (const auto* r = std::get_if<EllipseRegion>(&region))
    return {{ellipse(r->center, r->a, r->b, r->angle_deg)}};
  if (const auto* r = std::get_if<AnnulusRegion>(&region))
    return {{ellipse(r->center, r->outer, r->outer, 0)},
            reversed({ellipse(r->center, r->inner, r->inner, 0)})};
  const std::vector<Point2>& v = std::get<PolygonRegion>(region).vertices;
  const std::size_t n = v.size();
  BoundaryLoop loop;
  for (std::size_t k = 0; k < n; ++k)
    loop.push_back(edge(v[k], v[(k + 1) % n], static_cast<int>(k)));
  // Written clockwise: run it the other way, each edge keeping its number.
  double area2 = 0;
  for (std::size_t k = 0; k < n; ++k)
    area2 += v[k].x * v[(k + 1) % n].y - v[(k + 1) % n].x * v[k].y;
  if (area2 >= 0) return {loop};
  BoundaryLoop ccw = reversed(loop);
  for (std::size_t k = 0; k < n; ++k) ccw[k].face = static_cast<int>(n - 1 - k);
  return {ccw};
}
}  // namespace

std::vector<BoundaryLoop> shape_boundary(const Shape& shape) {
  std::vector<BoundaryLoop> loops = region_loops(shape.region);
  for (const Region& hole : shape.holes)
    for (BoundaryLoop& loop : region_loops(hole)) loops.push_back(reversed(std::move(loop)));
  return loops;
}

Point2 piece_point(const BoundaryPiece& piece, double t) {
  if (piece.kind == BoundaryPiece::Kind::edge)
    return {piece.a.x + t * (piece.b.x - piece.a.x), piece.a.y + t * (piece.b.y - piece.a.y)};
  const double theta = 2.0 * std::numbers::pi * (piece.counter_clockwise ? t : -t);
  const Point2 c = piece.center;
  return turn_point({c.x + piece.ra * std::cos(theta), c.y + piece.rb * std::sin(theta)}, c,
                    piece.angle_deg);
}

double piece_parameter(const BoundaryPiece& piece, Point2 p) {
  if (piece.kind == BoundaryPiece::Kind::edge) {
    const double dx = piece.b.x - piece.a.x, dy = piece.b.y - piece.a.y;
    const double t = ((p.x - piece.a.x) * dx + (p.y - piece.a.y) * dy) / (dx * dx + dy * dy);
    return std::clamp(t, 0.0, 1.0);
  }
  const Point2 c = piece.center;
  const Point2 q = unturn_point(p, c, piece.angle_deg);
  const double theta = std::atan2((q.y - c.y) / piece.rb, (q.x - c.x) / piece.ra);
  double t = (piece.counter_clockwise ? theta : -theta) / (2.0 * std::numbers::pi);
  t -= std::floor(t);
  return t < 1.0 ? t : 0.0;
}

}  // namespace mpsolid
