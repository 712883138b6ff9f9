#pragma once
// The part of a body's surface a [loads.NAME] table selects (README,
// "loads"): face = a rectangle's "bottom", "right", "top" or "left" (before
// it is turned) or a polygon's edge number (from vertex k to k + 1, counted
// from 1); box = { x = [x0, x1], y = [y0, y1] }; half_plane = { point =
// [x, y], normal = [nx, ny] } (the side the normal points to); at most one of
// them, the whole surface without. In space: face = a box's "bottom",
// "right", "top", "left", "back" or "front", a cylinder's "side", "base" or
// "top", an extrusion's section's faces and "back", "front"
// (src/core/region3_boundary.hpp); box = { x, y, z }; half_space = { point
// = [x, y, z], normal = [nx, ny, nz] }. Every problem is an InputError
// naming the file, the key and what is allowed; so is a selection that
// selects nothing at the case's l0.
#include <string>

#include "src/case/case_spec.hpp"
#include "src/case/table_reader.hpp"

namespace mpsolid {

SurfaceSelection read_selection(TableReader& r, const BodySpec& body, double l0, int dimension);

}  // namespace mpsolid
