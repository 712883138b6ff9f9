// Regions and shapes (src/core/region.hpp): which lattice sites a body
// holds, against plain references (rectangles' spans, the union of the
// pieces a shape is cut into, areas), and the polygon and containment
// checks the case reader makes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <utility>
#include <vector>

#include "src/core/region.hpp"

namespace mpsolid {
namespace {

using Sites = std::vector<Point2>;

std::set<std::pair<double, double>> as_set(const Sites& sites) {
  std::set<std::pair<double, double>> out;
  for (const Point2& p : sites) out.insert({p.x, p.y});
  return out;
}

bool same_bits(const Sites& a, const Sites& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].x != b[i].x || a[i].y != b[i].y) return false;
  return true;
}

Shape shape_of(Region r, std::vector<Region> holes = {}) {
  return Shape{std::move(r), std::move(holes)};
}

RectangleRegion rectangle(double x0, double x1, double y0, double y1) {
  RectangleRegion r;
  r.x[0] = x0;
  r.x[1] = x1;
  r.y[0] = y0;
  r.y[1] = y1;
  return r;
}

PolygonRegion corners(const RectangleRegion& r, bool clockwise) {
  PolygonRegion p{{{r.x[0], r.y[0]}, {r.x[1], r.y[0]}, {r.x[1], r.y[1]}, {r.x[0], r.y[1]}}};
  if (clockwise) std::reverse(p.vertices.begin(), p.vertices.end());
  return p;
}

TEST(Region, RectangleFillIsItsHalfOpenLatticeSpan) {
  // 0.1 / 0.002 is not exactly 50 in binary: the span's slack keeps 50 sites.
  const Sites sites = fill_shape(shape_of(rectangle(0.0, 0.1, -0.02, 0.02)), 0.002);
  ASSERT_EQ(sites.size(), 50u * 20u);
  EXPECT_EQ(sites.front().x, 0.5 * 0.002);
  EXPECT_EQ(sites.front().y, -9.5 * 0.002);
  EXPECT_EQ(sites[1].x, 1.5 * 0.002);  // row by row: x inner
  EXPECT_EQ(count_shape_sites(shape_of(rectangle(0.0, 0.1, -0.02, 0.02)), 0.002), 1000);
}

TEST(Region, RectangleWrittenAsAPolygonHoldsTheSameSitesInTheSameOrder) {
  // Edges on lattice lines, and edges through site centres (sites on the
  // left and bottom edges belong to the body, on the right and top not).
  for (const double l0 : {0.002, 0.001, 0.0005})
    for (const RectangleRegion& r :
         {rectangle(0.0, 0.1, -0.02, 0.02), rectangle(-0.006, 0.0, -0.03, 0.03),
          rectangle(0.5 * l0, 10.5 * l0, 2.5 * l0, 7.5 * l0),
          rectangle(-3.5 * l0, 4.0 * l0, -1.5 * l0, 0.5 * l0)})
      for (const bool clockwise : {false, true}) {
        SCOPED_TRACE(testing::Message() << "l0 " << l0 << " x " << r.x[0] << " " << r.x[1]
                                        << " clockwise " << clockwise);
        const Sites a = fill_shape(shape_of(r), l0);
        const Sites b = fill_shape(shape_of(corners(r, clockwise)), l0);
        EXPECT_FALSE(a.empty());
        EXPECT_TRUE(same_bits(a, b)) << a.size() << " against " << b.size() << " sites";
      }
}

TEST(Region, TwoPolygonsSharingAnEdgeSplitItsSites) {
  // A square cut along its diagonal, which passes through site centres.
  const double l0 = 0.001, L = 10 * l0;
  const PolygonRegion lower{{{0, 0}, {L, 0}, {L, L}}}, upper{{{0, 0}, {L, L}, {0, L}}};
  const auto a = as_set(fill_shape(shape_of(lower), l0));
  const auto b = as_set(fill_shape(shape_of(upper), l0));
  const auto square = as_set(fill_shape(shape_of(rectangle(0, L, 0, L)), l0));
  std::set<std::pair<double, double>> both;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::inserter(both, both.begin()));
  EXPECT_TRUE(both.empty()) << both.size() << " sites in both halves";
  std::set<std::pair<double, double>> all = a;
  all.insert(b.begin(), b.end());
  EXPECT_EQ(all, square);
}

TEST(Region, ConcavePolygonIsTheUnionOfItsPieces) {
  // An L: a 20 x 5 bar and a 5 x 15 bar on its left end.
  const double l0 = 0.001;
  const PolygonRegion ell{
      {{0, 0}, {0.02, 0}, {0.02, 0.005}, {0.005, 0.005}, {0.005, 0.02}, {0, 0.02}}};
  auto pieces = as_set(fill_shape(shape_of(rectangle(0, 0.02, 0, 0.005)), l0));
  const auto upright = as_set(fill_shape(shape_of(rectangle(0, 0.005, 0.005, 0.02)), l0));
  pieces.insert(upright.begin(), upright.end());
  EXPECT_EQ(as_set(fill_shape(shape_of(ell), l0)), pieces);
  EXPECT_NEAR(region_area(ell), 0.02 * 0.005 + 0.005 * 0.015, 1e-15);
}

TEST(Region, FillRowByRowAgreesWithThePointTest) {
  // A star (concave, slanted edges through many rows) with a polygon hole:
  // the fill's crossings per row against region_contains at every site.
  const double l0 = 0.0005;
  PolygonRegion star, notch{{{-0.002, -0.001}, {0.003, -0.0015}, {0.001, 0.002}}};
  for (int k = 0; k < 14; ++k) {
    const double t = 2 * std::numbers::pi * k / 14, r = k % 2 ? 0.006 : 0.015;
    star.vertices.push_back({0.0003 + r * std::cos(t), -0.0002 + r * std::sin(t)});
  }
  const Shape shape = shape_of(star, {notch});
  const auto filled = as_set(fill_shape(shape, l0));
  std::set<std::pair<double, double>> tested;
  for (int m = -40; m < 40; ++m)
    for (int k = -40; k < 40; ++k) {
      const Point2 p{(k + 0.5) * l0, (m + 0.5) * l0};
      if (region_contains(star, p) && !region_contains(notch, p)) tested.insert({p.x, p.y});
    }
  EXPECT_EQ(filled, tested);
  EXPECT_GT(filled.size(), 500u);
}

TEST(Region, HolesRemoveTheirSites) {
  const double l0 = 0.001;
  const RectangleRegion plate = rectangle(0, 0.03, 0, 0.02),
                        cut = rectangle(0.01, 0.02, 0.005, 0.015);
  auto expected = as_set(fill_shape(shape_of(plate), l0));
  for (const auto& s : as_set(fill_shape(shape_of(cut), l0))) expected.erase(s);
  EXPECT_EQ(as_set(fill_shape(shape_of(plate, {cut}), l0)), expected);
  // An annulus is a disk with a disk cut out.
  const CircleRegion outer{{0.001, -0.002}, 0.02}, inner{{0.001, -0.002}, 0.012};
  EXPECT_TRUE(same_bits(fill_shape(shape_of(AnnulusRegion{{0.001, -0.002}, 0.012, 0.02}), l0),
                        fill_shape(shape_of(outer, {inner}), l0)));
}

TEST(Region, CurvesHoldTheSitesStrictlyInside) {
  const double l0 = 0.001;
  const CircleRegion disk{{0.0, 0.0}, 0.0105};
  for (const Point2& p : fill_shape(shape_of(disk), l0))
    EXPECT_LT(p.x * p.x + p.y * p.y, disk.radius * disk.radius);
  // A circle as an ellipse of equal semi-axes, at any angle, and a square
  // turned a quarter turn hold the same sites.
  EXPECT_EQ(as_set(fill_shape(shape_of(disk), l0)),
            as_set(fill_shape(shape_of(EllipseRegion{{0, 0}, 0.0105, 0.0105, 30.0}), l0)));
  RectangleRegion turned = rectangle(-0.01, 0.01, -0.01, 0.01);
  turned.angle_deg = 90;
  EXPECT_EQ(as_set(fill_shape(shape_of(turned), l0)),
            as_set(fill_shape(shape_of(rectangle(-0.01, 0.01, -0.01, 0.01)), l0)));
}

TEST(Region, TurnedShapesHoldTheirAreaInSites) {
  // Sites times l0^2 against the exact area: the difference is a boundary
  // effect, well under a quarter of the perimeter (about 0.1 m) times l0.
  const double l0 = 0.0005;
  RectangleRegion r = rectangle(0, 0.04, 0, 0.01);
  r.angle_deg = 30;
  const EllipseRegion e{{0.1, 0.0}, 0.02, 0.008, -40.0};
  for (const Region& region : {Region(r), Region(e)}) {
    const double area = region_area(region);
    const double sites = static_cast<double>(count_shape_sites(shape_of(region), l0)) * l0 * l0;
    EXPECT_NEAR(sites, area, 0.25 * 0.1 * l0) << region_kind(region);
  }
}

TEST(Region, DiskAreaConvergesWithTheSpacing) {
  // Off the lattice's symmetry lines, so the count is a generic one.
  const CircleRegion disk{{0.00013, 0.00007}, 0.01};
  double finest = 1.0;
  for (const double l0 : {disk.radius / 5, disk.radius / 10, disk.radius / 20, disk.radius / 40}) {
    const double sites = static_cast<double>(count_shape_sites(shape_of(disk), l0));
    finest = std::abs(sites * l0 * l0 / region_area(disk) - 1.0);
    EXPECT_LT(finest, 2.0 * l0 / disk.radius) << "l0 = r / " << disk.radius / l0;
  }
  EXPECT_LT(finest, 0.01);
}

TEST(Region, PolygonProblemsNameTheEdges) {
  EXPECT_TRUE(polygon_problems(PolygonRegion{{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}).empty());
  EXPECT_TRUE(polygon_problems(PolygonRegion{{{0, 0}, {0, 1}, {1, 1}, {1, 0}}}).empty());
  const auto bow = polygon_problems(PolygonRegion{{{0, 0}, {1, 1}, {1, 0}, {0, 1}}});
  ASSERT_EQ(bow.size(), 1u);
  EXPECT_EQ(bow[0], "edges 1 (from vertex 1 to 2) and 3 (from vertex 3 to 4) cross at (0.5, 0.5)");
  // A spike that doubles back along its own edge.
  const auto spike = polygon_problems(PolygonRegion{{{0, 0}, {2, 0}, {1, 0}, {1, 1}}});
  EXPECT_FALSE(spike.empty());
  // A vertex touching another edge.
  EXPECT_FALSE(polygon_problems(PolygonRegion{{{0, 0}, {2, 0}, {2, 2}, {1, 0}, {0, 2}}}).empty());
  EXPECT_EQ(polygon_problems(PolygonRegion{{{0, 0}, {1, 0}, {0, 0}, {0, 1}}}).at(0),
            "vertices 1 and 3 are the same point (0, 0)");
  EXPECT_NE(polygon_problems(PolygonRegion{{{0, 0}, {1, 0}}}).at(0).find("at least 3"),
            std::string::npos);
  EXPECT_NE(polygon_problems(PolygonRegion{{{0, 0}, {1, 1}, {2, 2}}}).at(0).find("no area"),
            std::string::npos);
}

TEST(Region, WithinAndOverlap) {
  const RectangleRegion plate = rectangle(0, 0.03, 0, 0.02);
  const CircleRegion hole{{0.015, 0.01}, 0.005};
  EXPECT_TRUE(region_within(hole, plate));
  EXPECT_FALSE(region_within(CircleRegion{{0.028, 0.01}, 0.005}, plate));
  EXPECT_TRUE(region_within(CircleRegion{{0.025, 0.01}, 0.005}, plate));  // touches the edge
  // A pin in the hole does not overlap the plate; a larger one does.
  EXPECT_FALSE(shapes_overlap(shape_of(plate, {hole}), shape_of(hole)));
  EXPECT_TRUE(
      shapes_overlap(shape_of(plate, {hole}), shape_of(CircleRegion{{0.015, 0.01}, 0.006})));
  // Rectangles sharing an edge, and a disk resting on one, touch only.
  EXPECT_FALSE(shapes_overlap(shape_of(plate), shape_of(rectangle(0.03, 0.04, 0, 0.02))));
  EXPECT_FALSE(shapes_overlap(shape_of(plate), shape_of(CircleRegion{{0.015, 0.03}, 0.01})));
  EXPECT_TRUE(shapes_overlap(shape_of(plate), shape_of(CircleRegion{{0.015, 0.029}, 0.01})));
}

}  // namespace
}  // namespace mpsolid
