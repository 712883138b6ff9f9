#include "src/case/selection_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "src/core/region3_boundary.hpp"
#include "src/core/region_boundary.hpp"
#include "src/core/surface3.hpp"

namespace mpsolid {

namespace {
const std::vector<std::string> kSelections = {"face", "box", "half_plane", "half_space"};

// A 3D body's face by its name (src/core/region3_boundary.hpp): a string,
// or an extruded polygon's edge number.
int read_face3(TableReader& r, const BodySpec& body) {
  const TomlValue& v = r.require("face", "the face to load");
  const std::vector<std::string> names = region3_face_names(body.shape3.region);
  const char* kind = region3_kind(body.shape3.region);
  if (names.empty())
    r.fail("face", fmt::format("bodies.{} is shaped as a {}, which has no named faces; select "
                               "with box or half_space",
                               body.name, kind));
  const std::string name = v.is_string()    ? r.string(v, "face")
                           : v.is_integer() ? std::to_string(v.as_integer())
                                            : describe(v);
  for (std::size_t k = 0; k < names.size(); ++k)
    if (name == names[k]) return static_cast<int>(k);
  r.fail("face", fmt::format("unknown face {} of the {} bodies.{} (allowed: {})", describe(v), kind,
                             body.name, join(names)));
}

int read_face(TableReader& r, const BodySpec& body) {
  const TomlValue& v = r.require("face", "the face to load");
  if (std::holds_alternative<RectangleRegion>(body.shape.region)) {
    const std::string name = r.string(v, "face", "bottom, right, top or left");
    for (int k = 0; k < 4; ++k)
      if (name == kRectangleFaces[k]) return k;
    r.fail("face", fmt::format("unknown face '{}' of the rectangle bodies.{} (allowed: bottom, "
                               "right, top, left, as before it is turned)",
                               name, body.name));
  }
  if (const auto* polygon = std::get_if<PolygonRegion>(&body.shape.region)) {
    const std::size_t n = polygon->vertices.size();
    const double edge = r.number(v, "face", "an edge number");
    r.range_check("face", edge,
                  edge >= 1 && edge <= static_cast<double>(n) && edge == std::floor(edge),
                  fmt::format("an edge number 1 to {} (edge k runs from vertex k to k + 1)", n));
    return static_cast<int>(edge) - 1;
  }
  r.fail("face", fmt::format("bodies.{} is shaped as {}: only rectangles and polygons have named "
                             "faces; select with box or half_plane",
                             body.name, region_kind(body.shape.region)));
}

// { x = [x0, x1], y = [y0, y1] } (z = [z0, z1] too in space).
Box3 read_box(TableReader& r, int dimension) {
  const TomlValue& v =
      r.subtable("box", dimension == 3 ? "{ x = [x0, x1], y = [y0, y1], z = [z0, z1] } in m"
                                       : "{ x = [x0, x1], y = [y0, y1] } in m");
  TableReader box(v, r.key_path("box"), r.file());
  double range[3][2] = {};
  const char* axes[3] = {"x", "y", "z"};
  for (int a = 0; a < dimension; ++a) {
    box.pair(axes[a], fmt::format("the box's {0} range [{0}0, {0}1] in m", axes[a]), range[a]);
    if (!(range[a][0] <= range[a][1]))
      box.fail(axes[a], fmt::format("needs {0}0 <= {0}1, got [{1}, {2}]", axes[a], range[a][0],
                                    range[a][1]));
  }
  box.finish();
  return {{range[0][0], range[1][0], range[2][0]}, {range[0][1], range[1][1], range[2][1]}};
}

// A half-plane's line (a half-space's plane in space): a point on it and
// the normal that points to the side selected.
void read_half_plane(TableReader& r, SurfaceSelection& s, int dimension) {
  const std::string key = dimension == 3 ? "half_space" : "half_plane";
  const TomlValue& v =
      r.subtable(key, dimension == 3 ? "{ point = [x, y, z], normal = [nx, ny, nz] }"
                                     : "{ point = [x, y], normal = [nx, ny] }");
  TableReader plane(v, r.key_path(key), r.file());
  double point[3] = {0, 0, 0}, normal[3] = {0, 0, 0};
  plane.numbers(
      "point",
      dimension == 3 ? "a point [x, y, z] on the plane, in m" : "a point [x, y] on the line, in m",
      point, dimension);
  plane.numbers("normal",
                dimension == 3 ? "[nx, ny, nz]: the side selected" : "[nx, ny]: the side selected",
                normal, dimension);
  if (!(std::hypot(normal[0], normal[1], normal[2]) > 0))
    plane.fail("normal", dimension == 3 ? "needs a direction, got [0, 0, 0]"
                                        : "needs a direction, got [0, 0]");
  plane.finish();
  s.point = {point[0], point[1], point[2]};
  s.normal = {normal[0], normal[1], normal[2]};
}

// How many pieces of the body's surface the selection takes at l0.
std::size_t selected_pieces(TableReader& r, const BodySpec& body, double l0, int dimension,
                            const SurfaceSelection& s) {
  if (dimension == 3)
    return select_quads(build_surface3(body.shape3, fill_shape3(body.shape3, l0), l0), s).size();
  Surface surface;
  try {
    surface = build_surface(body.shape, fill_shape(body.shape, l0), l0);
  } catch (const std::invalid_argument& e) {
    r.fail("body",
           fmt::format("a pressure needs bodies.{}'s surface, and {}", body.name, e.what()));
  }
  return select_segments(surface, s).size();
}
}  // namespace

SurfaceSelection read_selection(TableReader& r, const BodySpec& body, double l0, int dimension) {
  SurfaceSelection s;
  const std::string plane_key = dimension == 3 ? "half_space" : "half_plane";
  const std::string choices = "face, box and " + plane_key;
  std::string given;
  for (const std::string& key : kSelections)
    if (r.has(key)) {
      if (key == "half_plane" || key == "half_space")
        if (key != plane_key)
          r.fail(key, fmt::format("a {}D case selects a side with {}", dimension, plane_key));
      if (!given.empty())
        r.fail(key, fmt::format("give one of {}; {} is given too", choices, given));
      given = key;
    }
  if (given == "face") {
    s.kind = SurfaceSelection::Kind::face;
    s.face = dimension == 3 ? read_face3(r, body) : read_face(r, body);
  } else if (given == "box") {
    s.kind = SurfaceSelection::Kind::box;
    s.box = read_box(r, dimension);
  } else if (given == plane_key) {
    s.kind = SurfaceSelection::Kind::half_plane;
    read_half_plane(r, s, dimension);
  }
  if (selected_pieces(r, body, l0, dimension, s) == 0) {
    std::string span;
    if (dimension == 3) {
      const Box3 b = body.shape3.bounds();
      span = fmt::format("its {} spans x = [{}, {}], y = [{}, {}], z = [{}, {}]",
                         region3_kind(body.shape3.region), b.lo.x, b.hi.x, b.lo.y, b.hi.y, b.lo.z,
                         b.hi.z);
    } else {
      const Box2 b = body.shape.bounds();
      span = fmt::format("its {} spans x = [{}, {}], y = [{}, {}]", region_kind(body.shape.region),
                         b.lo.x, b.hi.x, b.lo.y, b.hi.y);
    }
    r.fail(given.empty() ? "body" : given,
           fmt::format("selects no part of bodies.{}'s surface ({}); a piece of the surface "
                       "counts when its {} lies in the selection",
                       body.name, span, dimension == 3 ? "centre" : "midpoint"));
  }
  return s;
}

}  // namespace mpsolid
