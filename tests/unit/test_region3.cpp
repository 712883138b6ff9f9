// The 3D regions and their lattice fill: every site inside its region and
// none missed (against a plain scan of the lattice), the fill order (z,
// then y, then x), half-open boxes sharing a face split its sites, an
// extrusion's layers are the plane shape's fill to the bit, a cylinder
// along z holds the sites of the extruded circle, holes cut out, and the
// site counts converge on the exact volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <set>
#include <tuple>
#include <vector>

#include "src/core/geometry.hpp"
#include "src/core/region.hpp"
#include "src/core/region3.hpp"

namespace mpsolid {
namespace {

// Every lattice site in a box well round the shape, tested one by one.
std::vector<Point3> plain_scan(const Shape3& shape, double l0) {
  const Box3 b = shape.bounds();
  std::vector<Point3> sites;
  const auto span = [&](double lo, double hi) {
    return std::pair{static_cast<std::int64_t>(std::floor(lo / l0)) - 3,
                     static_cast<std::int64_t>(std::ceil(hi / l0)) + 3};
  };
  const auto [z0, z1] = span(b.lo.z, b.hi.z);
  const auto [y0, y1] = span(b.lo.y, b.hi.y);
  const auto [x0, x1] = span(b.lo.x, b.hi.x);
  for (std::int64_t n = z0; n <= z1; ++n)
    for (std::int64_t m = y0; m <= y1; ++m)
      for (std::int64_t k = x0; k <= x1; ++k) {
        const Point3 p{lattice_coordinate(k, l0), lattice_coordinate(m, l0),
                       lattice_coordinate(n, l0)};
        if (shape3_contains(shape, p)) sites.push_back(p);
      }
  return sites;
}

std::vector<Shape3> every_kind() {
  Shape plate{RectangleRegion{{0.0, 0.04}, {0.0, 0.03}, 0.0}, {CircleRegion{{0.02, 0.015}, 0.008}}};
  return {
      Shape3{BoxRegion{{0.0, 0.01}, {-0.004, 0.006}, {0.001, 0.007}}, {}},
      Shape3{CylinderRegion{{0.001, 0.002, 0.003}, {0.021, 0.012, 0.0}, 0.004}, {}},
      Shape3{SphereRegion{{0.003, -0.002, 0.001}, 0.0075}, {}},
      Shape3{ExtrusionRegion{plate, {-0.002, 0.004}}, {}},
      Shape3{BoxRegion{{0.0, 0.02}, {0.0, 0.02}, {0.0, 0.02}},
             {SphereRegion{{0.01, 0.01, 0.01}, 0.006},
              CylinderRegion{{0.003, 0.003, 0.0}, {0.003, 0.003, 0.02}, 0.002}}},
  };
}

TEST(Region3, TheFillHoldsEverySiteInsideAndNoOther) {
  const double l0 = 0.001;
  for (const Shape3& shape : every_kind()) {
    const std::vector<Point3> filled = fill_shape3(shape, l0), scanned = plain_scan(shape, l0);
    EXPECT_EQ(filled, scanned) << region3_kind(shape.region);
    EXPECT_EQ(count_shape3_sites(shape, l0), static_cast<std::int64_t>(filled.size()));
    const Box3 b = shape.bounds();
    for (const Point3& p : filled) {
      EXPECT_TRUE(p.x >= b.lo.x && p.x <= b.hi.x && p.y >= b.lo.y && p.y <= b.hi.y &&
                  p.z >= b.lo.z && p.z <= b.hi.z)
          << region3_kind(shape.region) << " site outside its bounds";
    }
  }
}

TEST(Region3, SitesComeLayerByLayerThenRowByRow) {
  for (const Shape3& shape : every_kind()) {
    const std::vector<Point3> sites = fill_shape3(shape, 0.001);
    ASSERT_FALSE(sites.empty());
    EXPECT_TRUE(std::is_sorted(sites.begin(), sites.end(), [](const Point3& a, const Point3& b) {
      return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x);
    })) << region3_kind(shape.region);
  }
}

TEST(Region3, BoxesSharingAFaceSplitItsSites) {
  const double l0 = 0.001;
  // The face at x = 0.005 lies on no site; the one at z = 0.0035 on a
  // layer of them (sites at (n + 1/2) l0).
  const BoxRegion whole{{0.0, 0.01}, {0.0, 0.004}, {0.0, 0.007}};
  const BoxRegion left{{0.0, 0.005}, {0.0, 0.004}, {0.0, 0.007}},
      right{{0.005, 0.01}, {0.0, 0.004}, {0.0, 0.007}};
  const BoxRegion low{{0.0, 0.01}, {0.0, 0.004}, {0.0, 0.0035}},
      high{{0.0, 0.01}, {0.0, 0.004}, {0.0035, 0.007}};
  const auto n = [&](const BoxRegion& b) { return count_shape3_sites(Shape3{b, {}}, l0); };
  EXPECT_EQ(n(whole), 10 * 4 * 7);
  EXPECT_EQ(n(left) + n(right), n(whole));
  EXPECT_EQ(n(low) + n(high), n(whole));
  std::set<std::tuple<double, double, double>> seen;
  for (const BoxRegion& b : {low, high})
    for (const Point3& p : fill_shape3(Shape3{b, {}}, l0))
      EXPECT_TRUE(seen.insert({p.x, p.y, p.z}).second) << "a site in both halves";
}

TEST(Region3, AnExtrusionsLayersAreThePlaneShapesFill) {
  const double l0 = 0.0005;
  const Shape section{PolygonRegion{{{0.0, 0.0}, {0.012, 0.002}, {0.009, 0.011}, {0.004, 0.006}}},
                      {CircleRegion{{0.007, 0.004}, 0.0015}}};
  const std::vector<Point2> plane = fill_shape(section, l0);
  const std::vector<Point3> slab =
      fill_shape3(Shape3{ExtrusionRegion{section, {0.0, 0.003}}, {}}, l0);
  ASSERT_EQ(slab.size(), 6 * plane.size());
  for (std::size_t i = 0; i < slab.size(); ++i) {
    const Point2& q = plane[i % plane.size()];
    EXPECT_EQ(slab[i].x, q.x);
    EXPECT_EQ(slab[i].y, q.y);
    EXPECT_EQ(slab[i].z, lattice_coordinate(static_cast<std::int64_t>(i / plane.size()), l0));
  }
}

TEST(Region3, ACylinderAlongZHoldsTheExtrudedCirclesSites) {
  const double l0 = 0.001;
  const Shape3 cylinder{CylinderRegion{{0.0103, 0.0087, 0.002}, {0.0103, 0.0087, 0.009}, 0.0061},
                        {}};
  const Shape3 extruded{
      ExtrusionRegion{Shape{CircleRegion{{0.0103, 0.0087}, 0.0061}, {}}, {0.002, 0.009}}, {}};
  EXPECT_EQ(fill_shape3(cylinder, l0), fill_shape3(extruded, l0));
}

TEST(Region3, HolesAreCutOut) {
  const double l0 = 0.001;
  const Shape3 block{BoxRegion{{0.0, 0.02}, {0.0, 0.02}, {0.0, 0.02}}, {}};
  const Shape3 ball{SphereRegion{{0.01, 0.01, 0.01}, 0.006}, {}};
  const Shape3 holed{block.region, {ball.region}};
  EXPECT_EQ(count_shape3_sites(holed, l0),
            count_shape3_sites(block, l0) - count_shape3_sites(ball, l0));
  for (const Point3& p : fill_shape3(holed, l0)) EXPECT_FALSE(region3_contains(ball.region, p));
}

TEST(Region3, SiteCountsConvergeOnTheExactVolumes) {
  for (const Shape3& shape : every_kind()) {
    const double exact = region3_volume(shape.region) - (shape.holes.empty() ? 0.0 : [&] {
                           double v = 0;
                           for (const Region3& h : shape.holes) v += region3_volume(h);
                           return v;
                         }());
    double previous = 1;
    for (const double l0 : {0.001, 0.0005, 0.00025}) {
      const double filled = static_cast<double>(count_shape3_sites(shape, l0)) * l0 * l0 * l0;
      const double error = std::abs(filled / exact - 1);
      std::printf("%s at l0 %g: sites x l0^3 off the volume by %.3f %%\n",
                  region3_kind(shape.region), l0, 100 * error);
      EXPECT_LT(error, 0.03) << region3_kind(shape.region) << " at l0 " << l0;
      if (l0 < 0.001) {
        EXPECT_LT(error, previous + 0.005) << region3_kind(shape.region);
      }
      previous = error;
    }
  }
  // A cube and a sphere exactly: a box on lattice planes holds its volume,
  // and a sphere's volume is 4/3 pi r^3.
  EXPECT_DOUBLE_EQ(region3_volume(BoxRegion{{0.0, 0.002}, {0.0, 0.003}, {0.0, 0.004}}), 2.4e-8);
  EXPECT_DOUBLE_EQ(region3_volume(SphereRegion{{}, 0.5}), std::numbers::pi / 6);
  EXPECT_DOUBLE_EQ(region3_volume(CylinderRegion{{0, 0, 0}, {0.0, 3.0, 4.0}, 1.0}),
                   5 * std::numbers::pi);
}

}  // namespace
}  // namespace mpsolid
