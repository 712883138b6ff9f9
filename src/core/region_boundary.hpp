#pragma once
// A shape's boundary as closed loops of exact pieces (straight edges and
// whole ellipses), each loop running with the body on its left: the
// region's outer loop counter-clockwise, a hole's loop clockwise (an
// annulus gives two loops, its inner circle clockwise). The surfaces of
// src/core/surface.hpp place their nodes on these pieces, so a straight face
// is exactly straight and a circle is the circle. A third dimension adds
// closed surfaces of patches beside them.
#include <string>
#include <vector>

#include "src/core/region.hpp"

namespace mpsolid {

struct BoundaryPiece {
  enum class Kind { edge, ellipse };
  Kind kind = Kind::edge;
  // An edge from a to b.
  Point2 a, b;
  // A whole ellipse: centre, semi-axes along its turned axes, turn (degrees),
  // and its sense (counter-clockwise or not).
  Point2 center;
  double ra = 0, rb = 0, angle_deg = 0;
  bool counter_clockwise = true;
  // A named face the case can select: a rectangle's 0 bottom, 1 right, 2 top,
  // 3 left (before it is turned), a polygon's edge from vertex k + 1 as
  // written (counted from 0); -1 for curves and for holes' pieces.
  int face = -1;
};
using BoundaryLoop = std::vector<BoundaryPiece>;

// The loops of a shape: the region's first, then each hole's.
std::vector<BoundaryLoop> shape_boundary(const Shape& shape);

// The point at parameter t in [0, 1] along the piece, in its loop's sense.
Point2 piece_point(const BoundaryPiece& piece, double t);
// The parameter of the point of the piece a point projects onto: for an
// edge the nearest point (clamped to [0, 1]); for an ellipse the point on
// the ray from its centre through p in the ellipse's own scaled frame (the
// nearest point for a circle), t in [0, 1).
double piece_parameter(const BoundaryPiece& piece, Point2 p);

// Why the shape's loops do not make its boundary, as a sentence, or empty:
// a hole that touches the region's edge or another hole (then the boundary
// is not the union of the loops).
std::string boundary_problem(const Shape& shape);

// The names of a rectangle's faces, by face index.
inline constexpr const char* kRectangleFaces[4] = {"bottom", "right", "top", "left"};

}  // namespace mpsolid
