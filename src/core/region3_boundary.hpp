#pragma once
// The surface of a region of space and of a 3D shape, as the points nearest
// a given point: a box's six faces, a cylinder's side and two caps, a
// sphere, an extrusion's side (its section's boundary loops swept along z)
// and its two caps. The surfaces of src/core/surface3.hpp place their nodes
// on these points, so a flat face is exactly flat and a sphere the sphere.
//
// Named faces, by index: a box's 0 bottom (y low), 1 right (x high), 2 top,
// 3 left, 4 back (z low), 5 front (z high); an extrusion's side takes its
// section's faces (a rectangle's four as in the plane, a polygon's edges
// counted from 0) and its caps come after them, back then front; a
// cylinder's 0 side, 1 base, 2 top. A sphere, a section's curves and every
// hole have none (-1).
#include <string>
#include <vector>

#include "src/core/region3.hpp"

namespace mpsolid {

struct SurfacePoint3 {
  Point3 at;
  int face = -1;
  double distance = 0;  // from the point asked about
};

// The point of the region's surface nearest p (for an extrusion's curved
// side, the point its section's projection gives: the nearest for a
// circle), with its face.
SurfacePoint3 nearest_region3_surface_point(const Region3& r, Point3 p);

// The same for a shape: the nearest point of its region's surface outside
// its holes or of a hole's surface inside its region (a hole's points have
// face -1).
SurfacePoint3 nearest_shape3_surface_point(const Shape3& shape, Point3 p);

// The names of a region's faces, by face index (empty for a sphere).
std::vector<std::string> region3_face_names(const Region3& r);

}  // namespace mpsolid
