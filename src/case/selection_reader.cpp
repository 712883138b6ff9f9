#include "src/case/selection_reader.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "src/core/region_boundary.hpp"

namespace mpsolid {

namespace {
const std::vector<std::string> kSelections = {"face", "box", "half_plane"};

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

Box2 read_box(TableReader& r) {
  const TomlValue& v = r.subtable("box", "{ x = [x0, x1], y = [y0, y1] } in m");
  TableReader box(v, r.key_path("box"), r.file());
  double x[2], y[2];
  box.pair("x", "the box's x range [x0, x1] in m", x);
  box.pair("y", "the box's y range [y0, y1] in m", y);
  if (!(x[0] <= x[1])) box.fail("x", fmt::format("needs x0 <= x1, got [{}, {}]", x[0], x[1]));
  if (!(y[0] <= y[1])) box.fail("y", fmt::format("needs y0 <= y1, got [{}, {}]", y[0], y[1]));
  box.finish();
  return {{x[0], y[0]}, {x[1], y[1]}};
}

void read_half_plane(TableReader& r, SurfaceSelection& s) {
  const TomlValue& v = r.subtable("half_plane", "{ point = [x, y], normal = [nx, ny] }");
  TableReader plane(v, r.key_path("half_plane"), r.file());
  double point[2], normal[2];
  plane.pair("point", "a point [x, y] on the line, in m", point);
  plane.pair("normal", "[nx, ny]: the side selected", normal);
  if (!(std::hypot(normal[0], normal[1]) > 0))
    plane.fail("normal", "needs a direction, got [0, 0]");
  plane.finish();
  s.point = {point[0], point[1]};
  s.normal = {normal[0], normal[1]};
}
}  // namespace

SurfaceSelection read_selection(TableReader& r, const BodySpec& body, double l0) {
  SurfaceSelection s;
  std::string given;
  for (const std::string& key : kSelections)
    if (r.has(key)) {
      if (!given.empty())
        r.fail(key, fmt::format("give one of face, box and half_plane; {} is given too", given));
      given = key;
    }
  if (given == "face") {
    s.kind = SurfaceSelection::Kind::face;
    s.face = read_face(r, body);
  } else if (given == "box") {
    s.kind = SurfaceSelection::Kind::box;
    s.box = read_box(r);
  } else if (given == "half_plane") {
    s.kind = SurfaceSelection::Kind::half_plane;
    read_half_plane(r, s);
  }
  Surface surface;
  try {
    surface = build_surface(body.shape, fill_shape(body.shape, l0), l0);
  } catch (const std::invalid_argument& e) {
    r.fail("body",
           fmt::format("a pressure needs bodies.{}'s surface, and {}", body.name, e.what()));
  }
  if (select_segments(surface, s).empty()) {
    const Box2 b = body.shape.bounds();
    r.fail(given.empty() ? "body" : given,
           fmt::format(
               "selects no part of bodies.{}'s surface (its {} spans x = [{}, {}], y = "
               "[{}, {}]); a piece of the surface counts when its midpoint lies in the selection",
               body.name, region_kind(body.shape.region), b.lo.x, b.hi.x, b.lo.y, b.hi.y));
  }
  return s;
}

}  // namespace mpsolid
