#pragma once
// A body's shape from its [bodies.NAME] table (docs/running.md, "Shapes"):
//   shape = "rectangle" (the default): x = [x0, x1], y = [y0, y1], angle
//     (degrees, counter-clockwise about the centre; default 0);
//   shape = "circle": center = [x, y], radius;
//   shape = "ellipse": center, semi_axes = [a, b], angle;
//   shape = "annulus": center, radii = [inner, outer];
//   shape = "polygon": vertices = [[x, y], ...] or vertices_file (a CSV
//     file of x, y lines, relative to the case file);
//   holes = [{ shape = ..., ... }, ...]: regions cut out, each inside the
//     body's region.
// In space (dimension = 3):
//   shape = "box" (the default): x = [x0, x1], y = [y0, y1], z = [z0, z1];
//   shape = "cylinder": base = [x, y, z], top = [x, y, z], radius;
//   shape = "sphere": center = [x, y, z], radius;
//   shape = "extrusion": section = { a plane shape's table, holes included },
//     z = [z0, z1]: the section swept along z;
//   holes = [{ shape = ..., ... }, ...]: regions of space cut out, each
//     meeting the body's region.
// Every problem is an InputError naming the file (and line), the key and
// what is allowed.
#include <string>

#include "src/case/table_reader.hpp"
#include "src/core/region.hpp"
#include "src/core/region3.hpp"

namespace mpsolid {

// The shape of the body whose table `r` reads; `case_file` is the case's
// path (vertex files are found beside it).
Shape read_shape(TableReader& r, const std::string& case_file);
// The same in space.
Shape3 read_shape3(TableReader& r, const std::string& case_file);

}  // namespace mpsolid
