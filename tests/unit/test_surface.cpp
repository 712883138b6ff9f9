// Surfaces (src/core/surface.hpp) and the pressure on them
// (src/core/loads.hpp): nodes on the true boundary, weights that follow any
// affine motion, faces that add up to their lengths, a circle's chords that
// converge to its perimeter, and a uniform pressure on a closed boundary
// that gives no net force or torque in any configuration.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "src/core/loads.hpp"
#include "src/core/region_boundary.hpp"
#include "src/core/surface.hpp"

namespace mpsolid {
namespace {

RectangleRegion rectangle(double x0, double x1, double y0, double y1, double angle = 0) {
  RectangleRegion r;
  r.x[0] = x0;
  r.x[1] = x1;
  r.y[0] = y0;
  r.y[1] = y1;
  r.angle_deg = angle;
  return r;
}

// An L-shaped concave polygon, written clockwise.
PolygonRegion ell() {
  return PolygonRegion{
      {{0, 0}, {0, 0.03}, {0.012, 0.03}, {0.012, 0.012}, {0.03, 0.012}, {0.03, 0}}};
}

struct Body {
  Shape shape;
  double l0;
  std::vector<Point2> sites;
  Surface surface;
  Body(Shape s, double spacing) : shape(std::move(s)), l0(spacing) {
    sites = fill_shape(shape, l0);
    surface = build_surface(shape, sites, l0);
  }
};

double segment_length(const Surface& s, std::size_t k) {
  const Point2 a = s.node_ref[k], b = s.node_ref[s.next[k]];
  return std::hypot(b.x - a.x, b.y - a.y);
}

TEST(Surface, NodesLieOnTheBoundaryAndFollowAffineMotion) {
  const std::vector<Shape> shapes = {
      {rectangle(0, 0.02, 0, 0.01, 17), {}},           {CircleRegion{{0.001, -0.002}, 0.0103}, {}},
      {EllipseRegion{{0, 0}, 0.012, 0.007, 30}, {}},   {AnnulusRegion{{0, 0}, 0.004, 0.01}, {}},
      {ell(), {CircleRegion{{0.005, 0.005}, 0.0025}}},
  };
  for (const Shape& shape : shapes) {
    const Body b(shape, 0.001);
    ASSERT_GT(b.surface.nodes(), 8u);
    // x -> A x + c, applied to the sites, moves each node the same way.
    const double a11 = 1.3, a12 = -0.4, a21 = 0.25, a22 = 0.8, cx = 0.3, cy = -0.1;
    std::vector<double> x, y;
    for (const Point2& p : b.sites) {
      x.push_back(a11 * p.x + a12 * p.y + cx);
      y.push_back(a21 * p.x + a22 * p.y + cy);
    }
    for (std::size_t k = 0; k < b.surface.nodes(); ++k) {
      const Point2 r = b.surface.node_ref[k];
      double sum = 0;
      for (std::uint32_t w = b.surface.offsets[k]; w < b.surface.offsets[k + 1]; ++w)
        sum += b.surface.weight[w];
      EXPECT_NEAR(sum, 1.0, 1e-12);
      const Point2 now = node_position(b.surface, k, x.data(), y.data(), 0);
      EXPECT_NEAR(now.x, a11 * r.x + a12 * r.y + cx, 1e-14);
      EXPECT_NEAR(now.y, a21 * r.x + a22 * r.y + cy, 1e-14);
      // On the shape's boundary.
      double nearest = 1;
      for (const BoundaryLoop& loop : shape_boundary(shape))
        for (const BoundaryPiece& piece : loop) {
          const Point2 q = piece_point(piece, piece_parameter(piece, r));
          nearest = std::min(nearest, std::hypot(q.x - r.x, q.y - r.y));
        }
      EXPECT_LT(nearest, 1e-15) << region_kind(shape.region);
      // A straight face's segment has the body on its left (a curve's chord
      // cuts inside its curve).
      if (b.surface.face[k] < 0) continue;
      const Point2 n = b.surface.node_ref[b.surface.next[k]];
      const double len = segment_length(b.surface, k);
      const Point2 mid{0.5 * (r.x + n.x), 0.5 * (r.y + n.y)};
      const double ix = -(n.y - r.y) / len, iy = (n.x - r.x) / len;  // inward
      EXPECT_TRUE(region_contains(shape.region, {mid.x + 1e-6 * ix, mid.y + 1e-6 * iy}));
      EXPECT_FALSE(region_contains(shape.region, {mid.x - 1e-6 * ix, mid.y - 1e-6 * iy}));
    }
  }
}

TEST(Surface, StraightFacesAddUpToTheirLengths) {
  for (const double angle : {0.0, 33.0}) {
    const Body b({rectangle(-0.006, 0.0, -0.03, 0.03, angle), {}}, 0.002);
    double face[4] = {0, 0, 0, 0};
    for (std::size_t k = 0; k < b.surface.nodes(); ++k)
      face[b.surface.face[k]] += segment_length(b.surface, k);
    EXPECT_NEAR(face[0], 0.006, 1e-17);
    EXPECT_NEAR(face[1], 0.06, 1e-16);
    EXPECT_NEAR(face[2], 0.006, 1e-17);
    EXPECT_NEAR(face[3], 0.06, 1e-16);
  }
  // A polygon's edges keep the numbers they are written with, clockwise too.
  const Body l({ell(), {}}, 0.001);
  std::vector<double> edge(6, 0.0);
  for (std::size_t k = 0; k < l.surface.nodes(); ++k)
    edge[l.surface.face[k]] += segment_length(l.surface, k);
  const std::vector<double> expected = {0.03, 0.012, 0.018, 0.018, 0.012, 0.03};
  for (std::size_t e = 0; e < 6; ++e) EXPECT_NEAR(edge[e], expected[e], 1e-15) << "edge " << e + 1;
}

TEST(Surface, ARectangleAsAPolygonHasTheSameSurface) {
  const Body rect({rectangle(0, 0.02, 0, 0.01), {}}, 0.001);
  const Body poly({PolygonRegion{{{0, 0}, {0.02, 0}, {0.02, 0.01}, {0, 0.01}}}, {}}, 0.001);
  ASSERT_EQ(rect.surface.nodes(), poly.surface.nodes());
  EXPECT_EQ(rect.surface.host, poly.surface.host);
  EXPECT_EQ(rect.surface.weight, poly.surface.weight);
  EXPECT_EQ(rect.surface.face, poly.surface.face);
}

TEST(Surface, ACirclesChordsConvergeToItsPerimeterAtSecondOrder) {
  const double r = 0.01;
  double previous = 0;
  for (const double l0 : {r / 5, r / 10, r / 20, r / 40}) {
    const Body b({CircleRegion{{0, 0}, r}, {}}, l0);
    double length = 0;
    for (std::size_t k = 0; k < b.surface.nodes(); ++k) length += segment_length(b.surface, k);
    const double error = 2 * std::numbers::pi * r - length;
    EXPECT_GT(error, 0);  // chords of a convex curve are shorter
    if (previous > 0) {
      EXPECT_LT(error, 0.4 * previous) << "l0 = " << l0;
    }
    previous = error;
  }
  EXPECT_LT(previous / (2 * std::numbers::pi * r), 2e-4);
}

// A uniform pressure on the whole surface, through make_pressure_surface and
// pressure_forces: the particles' forces, summed, and their torques.
void expect_balanced(const Body& b, const std::vector<double>& x, const std::vector<double>& y) {
  StepLoad load;
  load.surface =
      make_pressure_surface(b.surface, select_segments(b.surface, SurfaceSelection{}), 0, 1e5, 1.0);
  ParticleStore p;
  p.resize(b.sites.size());
  p.x = x;
  p.y = y;
  // The forces of a step starting here.
  std::vector<StepLoad> loads{load};
  activate_loads(p, loads, 0, 1e-6);
  const PressureSurface& ps = loads[0].surface;
  double fx = 0, fy = 0, torque = 0, scale = 0;
  for (std::size_t t = 0; t < ps.targets.size(); ++t) {
    const std::size_t i = ps.targets[t];
    fx += ps.target_fx[t];
    fy += ps.target_fy[t];
    torque += x[i] * ps.target_fy[t] - y[i] * ps.target_fx[t];
    scale += std::hypot(ps.target_fx[t], ps.target_fy[t]);
  }
  EXPECT_LT(std::hypot(fx, fy), 1e-13 * scale);
  EXPECT_LT(std::abs(torque), 1e-13 * scale * 0.05);
  EXPECT_GT(scale, 0);
}

TEST(Surface, UniformPressureGivesNoNetForceOrTorqueInAnyConfiguration) {
  const std::vector<Shape> shapes = {
      {CircleRegion{{0.002, 0.001}, 0.01}, {}},
      {ell(), {CircleRegion{{0.005, 0.005}, 0.0025}}},
      {AnnulusRegion{{0, 0}, 0.004, 0.01}, {}},
      {rectangle(0, 0.02, 0, 0.01, 25), {}},
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-3e-4, 3e-4);
  for (const Shape& shape : shapes) {
    const Body b(shape, 0.001);
    std::vector<double> x, y;
    for (const Point2& p : b.sites) {
      x.push_back(p.x);
      y.push_back(p.y);
    }
    expect_balanced(b, x, y);
    // A large, non-affine deformation with a rotation: bend, shear and noise.
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double u = x[i], v = y[i];
      x[i] = 0.01 + 1.4 * u + 0.3 * v + 8 * v * v + jitter(rng);
      y[i] = -0.02 - 0.5 * u + 0.7 * v + 12 * u * u + jitter(rng);
    }
    expect_balanced(b, x, y);
  }
}

TEST(Surface, SelectionsPickTheirSegments) {
  const Body b({rectangle(-0.006, 0.0, -0.03, 0.03), {}}, 0.002);
  const auto length_of = [&](const SurfaceSelection& sel) {
    double sum = 0;
    for (const std::uint32_t k : select_segments(b.surface, sel))
      sum += segment_length(b.surface, k);
    return sum;
  };
  EXPECT_NEAR(length_of({}), 0.132, 1e-15);
  SurfaceSelection face;
  face.kind = SurfaceSelection::Kind::face;
  face.face = 3;
  EXPECT_NEAR(length_of(face), 0.06, 1e-15);
  SurfaceSelection box;
  box.kind = SurfaceSelection::Kind::box;
  box.box = {{-0.001, 0.0005}, {0.01, 0.0095}};  // four segments of the right face
  EXPECT_NEAR(length_of(box), 0.008, 1e-15);
  SurfaceSelection half;
  half.kind = SurfaceSelection::Kind::half_plane;
  half.point = {0, 0.029};
  half.normal = {0, 1};  // the top face and the last segment of each side
  EXPECT_NEAR(length_of(half), 0.006 + 2 * 0.001, 1e-15);
  box.box = {{1, 1}, {2, 2}};
  EXPECT_TRUE(select_segments(b.surface, box).empty());

  // A half-plane through a disk's centre: the segments astride the line on
  // both sides, so the loaded half's area vector has no y part.
  const Body disk({CircleRegion{{0, 0}, 0.01}, {}}, 0.0005);
  SurfaceSelection left;
  left.kind = SurfaceSelection::Kind::half_plane;
  left.normal = {-1, 0};
  double ax = 0, ay = 0;
  for (const std::uint32_t k : select_segments(disk.surface, left)) {
    const Point2 a = disk.surface.node_ref[k], c = disk.surface.node_ref[disk.surface.next[k]];
    ax += c.y - a.y;
    ay -= c.x - a.x;
  }
  EXPECT_NEAR(ax, -0.02, 2e-5);  // the chord from top to bottom
  EXPECT_LT(std::abs(ay), 1e-15);
}

TEST(Surface, HolesThatTouchTheEdgeAreRefused) {
  const Shape notch{rectangle(0, 0.02, 0, 0.01), {CircleRegion{{0.01, 0.01}, 0.002}}};
  EXPECT_NE(boundary_problem(notch), "");
  EXPECT_THROW(build_surface(notch, fill_shape(notch, 0.001), 0.001), std::invalid_argument);
  const Shape two{rectangle(0, 0.02, 0, 0.01),
                  {CircleRegion{{0.006, 0.005}, 0.002}, CircleRegion{{0.009, 0.005}, 0.002}}};
  EXPECT_NE(boundary_problem(two), "");
  const Shape apart{rectangle(0, 0.02, 0, 0.01),
                    {CircleRegion{{0.005, 0.005}, 0.002}, CircleRegion{{0.012, 0.005}, 0.002}}};
  EXPECT_EQ(boundary_problem(apart), "");
}

}  // namespace
}  // namespace mpsolid
