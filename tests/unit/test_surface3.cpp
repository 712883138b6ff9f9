// Surfaces in space (src/core/surface3.hpp) and the pressure on them
// (src/core/loads.hpp): nodes on the shape's surface, weights that follow
// any affine motion, a box's faces exact (on the lattice's cell faces or
// not), a sphere's volume converging at second order, named faces and
// selections, and a uniform pressure
// on a closed surface that gives no net force or torque in any
// configuration, holes included.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "src/core/loads.hpp"
#include "src/core/region3_boundary.hpp"
#include "src/core/surface3.hpp"

namespace mpsolid {
namespace {

BoxRegion box(double x0, double x1, double y0, double y1, double z0, double z1) {
  BoxRegion b;
  b.x[0] = x0;
  b.x[1] = x1;
  b.y[0] = y0;
  b.y[1] = y1;
  b.z[0] = z0;
  b.z[1] = z1;
  return b;
}

struct Body3 {
  Shape3 shape;
  double l0;
  std::vector<Point3> sites;
  Surface3 surface;
  Body3(Shape3 s, double spacing) : shape(std::move(s)), l0(spacing) {
    sites = fill_shape3(shape, l0);
    surface = build_surface3(shape, sites, l0);
  }
};

// Boxes on and off the lattice's cell faces, a slanted cylinder, a sphere,
// a plate with a round hole through it (an extrusion of a holed rectangle)
// and a block with a spherical cavity.
std::vector<Shape3> shapes() {
  RectangleRegion plate;
  plate.x[1] = 0.012;
  plate.y[1] = 0.008;
  ExtrusionRegion holed{{plate, {CircleRegion{{0.005, 0.004}, 0.002}}}, {0.0, 0.004}};
  return {
      {box(0, 0.006, 0, 0.004, 0, 0.005), {}},
      {box(0.0003, 0.0063, -0.0004, 0.0036, 0.0002, 0.0052), {}},
      {CylinderRegion{{0.001, 0.0, -0.002}, {0.004, 0.003, 0.009}, 0.003}, {}},
      {SphereRegion{{0.0003, -0.0002, 0.0001}, 0.0045}, {}},
      {holed, {}},
      {box(0, 0.01, 0, 0.01, 0, 0.01), {SphereRegion{{0.005, 0.005, 0.005}, 0.0025}}},
  };
}

// The sum of the outward area vectors of the quadrilaterals `quads`, the
// nodes where `x`, `y`, `z` put them.
Eigen::Vector3d area_vector(const Surface3& s, const std::vector<std::uint32_t>& quads,
                            const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& z) {
  std::vector<std::uint32_t> corner;
  for (const std::uint32_t q : quads)
    corner.insert(corner.end(), &s.corner[4 * q], &s.corner[4 * q + 4]);
  std::vector<double> ax(s.nodes(), 0.0), ay(s.nodes(), 0.0), az(s.nodes(), 0.0);
  add_node_area_vectors(corner, {x.data(), y.data(), z.data()}, 1.0,
                        {ax.data(), ay.data(), az.data()});
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < s.nodes(); ++k) sum += Eigen::Vector3d(ax[k], ay[k], az[k]);
  return sum;
}

// The nodes' reference positions, axis by axis.
void reference(const Surface3& s, std::vector<double>& x, std::vector<double>& y,
               std::vector<double>& z) {
  for (const Point3& p : s.node_ref) {
    x.push_back(p.x);
    y.push_back(p.y);
    z.push_back(p.z);
  }
}

TEST(Surface3, NodesLieOnTheSurfaceAndFollowAffineMotion) {
  Eigen::Matrix3d a;
  a << 1.3, -0.4, 0.2, 0.25, 0.8, -0.1, 0.05, 0.3, 1.1;
  const Eigen::Vector3d c(0.3, -0.1, 0.2);
  for (const Shape3& shape : shapes()) {
    const Body3 b(shape, 0.001);
    ASSERT_GT(b.surface.quads(), 20u);
    std::vector<Eigen::Vector3d> moved;
    for (const Point3& p : b.sites) moved.push_back(a * Eigen::Vector3d(p.x, p.y, p.z) + c);
    for (std::size_t k = 0; k < b.surface.nodes(); ++k) {
      const Point3 r = b.surface.node_ref[k];
      double sum = 0;
      Eigen::Vector3d now = Eigen::Vector3d::Zero();
      for (std::uint32_t w = b.surface.offsets[k]; w < b.surface.offsets[k + 1]; ++w) {
        sum += b.surface.weight[w];
        now += b.surface.weight[w] * moved[b.surface.site[w]];
      }
      EXPECT_NEAR(sum, 1.0, 1e-12);
      EXPECT_LT((now - (a * Eigen::Vector3d(r.x, r.y, r.z) + c)).norm(), 1e-14);
      EXPECT_LT(nearest_shape3_surface_point(shape, r).distance, 1e-15)
          << region3_kind(shape.region);
    }
  }
}

TEST(Surface3, AClosedSurfaceSpansNoAreaAndABoxsFacesAreExact) {
  for (const Shape3& shape : shapes()) {
    const Body3 b(shape, 0.001);
    std::vector<double> x, y, z;
    reference(b.surface, x, y, z);
    const Eigen::Vector3d whole = area_vector(b.surface, select_quads(b.surface, {}), x, y, z);
    EXPECT_LT(whole.norm(), 1e-19) << region3_kind(shape.region);
  }
  // A box's faces, by name: the area of each, along its outward normal,
  // whether its faces lie on the lattice's cell faces or between them.
  for (const BoxRegion& region :
       {box(0, 0.006, 0, 0.004, 0, 0.005), box(0.0003, 0.0063, -0.0004, 0.0036, 0.0002, 0.0052)}) {
    const Body3 b({region, {}}, 0.001);
    std::vector<double> x, y, z;
    reference(b.surface, x, y, z);
    const std::vector<std::string> names = region3_face_names(b.shape.region);
    const Eigen::Vector3d expected[6] = {{0, -0.006 * 0.005, 0}, {0.004 * 0.005, 0, 0},
                                         {0, 0.006 * 0.005, 0},  {-0.004 * 0.005, 0, 0},
                                         {0, 0, -0.006 * 0.004}, {0, 0, 0.006 * 0.004}};
    for (int face = 0; face < 6; ++face) {
      SurfaceSelection by_name;
      by_name.kind = SurfaceSelection::Kind::face;
      by_name.face = face;
      const Eigen::Vector3d got = area_vector(b.surface, select_quads(b.surface, by_name), x, y, z);
      EXPECT_LT((got - expected[face]).norm(), 1e-19)
          << names[static_cast<std::size_t>(face)] << " of a box from x = " << region.x[0];
    }
  }
}

TEST(Surface3, ASpheresVolumeConvergesAtSecondOrderAndItsCapSpansItsDisc) {
  // The volume the mesh encloses (3.8 %, 0.93 %, 0.23 % short at 4, 8 and
  // 16 spacings per radius), and the cap above the plane z = h, whose area
  // vector is pi (r^2 - h^2) along z to the selection's edge, which follows
  // the quadrilaterals' centres.
  const double r = 0.005, h = 0.002;
  SurfaceSelection cap;
  cap.kind = SurfaceSelection::Kind::half_plane;
  cap.point = {0, 0, h};
  cap.normal = {0, 0, 1};
  double previous = 0;
  for (const double l0 : {r / 4, r / 8, r / 16}) {
    const Body3 b({SphereRegion{{0, 0, 0}, r}, {}}, l0);
    std::vector<double> x, y, z;
    reference(b.surface, x, y, z);
    const double ball = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const double error = (ball - enclosed_volume(b.surface.corner, {x.data(), y.data(), z.data()},
                                                 b.surface.nodes())) /
                         ball;
    EXPECT_GT(error, 0) << "l0 = " << l0;  // chords of a convex surface cut inside it
    if (previous > 0) {
      EXPECT_LT(error, 0.35 * previous) << "l0 = " << l0;
    }
    previous = error;
    const Eigen::Vector3d got = area_vector(b.surface, select_quads(b.surface, cap), x, y, z);
    const double disc = std::numbers::pi * (r * r - h * h);
    EXPECT_LT(std::hypot(got.x(), got.y()), 1e-12 * disc);  // symmetric
    EXPECT_NEAR(got.z(), disc, (l0 < r / 6 ? 0.015 : 0.07) * disc) << "l0 = " << l0;
  }
  EXPECT_LT(previous, 0.003);
}

TEST(Surface3, NamedFacesOfCylindersAndExtrusions) {
  // A cylinder along z: its base's area vector is -pi r^2 z, its top's +pi r^2 z
  // (to the discs' discretisation), its side's none.
  const double r = 0.004;
  const Body3 cyl({CylinderRegion{{0, 0, 0}, {0, 0, 0.01}, r}, {}}, 0.0005);
  std::vector<double> x, y, z;
  reference(cyl.surface, x, y, z);
  const auto face = [](int k) {
    SurfaceSelection s;
    s.kind = SurfaceSelection::Kind::face;
    s.face = k;
    return s;
  };
  const double disc = std::numbers::pi * r * r;
  const Eigen::Vector3d side =
      area_vector(cyl.surface, select_quads(cyl.surface, face(0)), x, y, z);
  const Eigen::Vector3d base =
      area_vector(cyl.surface, select_quads(cyl.surface, face(1)), x, y, z);
  const Eigen::Vector3d top = area_vector(cyl.surface, select_quads(cyl.surface, face(2)), x, y, z);
  EXPECT_LT(side.norm(), 1e-3 * disc);
  EXPECT_NEAR(base.z(), -disc, 0.02 * disc);
  EXPECT_NEAR(top.z(), disc, 0.02 * disc);
  // An extruded rectangle names its faces as a box does: its front is z high.
  RectangleRegion section;
  section.x[1] = 0.006;
  section.y[1] = 0.004;
  const Body3 slab({ExtrusionRegion{{section, {}}, {0.0, 0.003}}, {}}, 0.001);
  std::vector<double> sx, sy, sz;
  reference(slab.surface, sx, sy, sz);
  EXPECT_EQ(region3_face_names(slab.shape.region)[5], "front");
  const Eigen::Vector3d front =
      area_vector(slab.surface, select_quads(slab.surface, face(5)), sx, sy, sz);
  EXPECT_LT((front - Eigen::Vector3d(0, 0, 0.006 * 0.004)).norm(), 1e-20);
  const Eigen::Vector3d right =
      area_vector(slab.surface, select_quads(slab.surface, face(1)), sx, sy, sz);
  EXPECT_LT((right - Eigen::Vector3d(0.004 * 0.003, 0, 0)).norm(), 1e-20);
  // A hole's surface has no name.
  const Body3 cavity(shapes()[5], 0.001);
  std::size_t unnamed = 0;
  for (const std::int32_t f : cavity.surface.face) unnamed += f < 0 ? 1 : 0;
  EXPECT_GT(unnamed, 20u);
}

TEST(Surface3, BoxSelectionTakesTheQuadsWhoseCentresItHolds) {
  const Body3 b({box(0, 0.006, 0, 0.004, 0, 0.005), {}}, 0.001);
  SurfaceSelection s;
  s.kind = SurfaceSelection::Kind::box;
  s.box = {{0.0058, 0.0, 0.0}, {0.007, 0.002, 0.005}};  // the right face's lower half
  std::vector<double> x, y, z;
  reference(b.surface, x, y, z);
  const Eigen::Vector3d got = area_vector(b.surface, select_quads(b.surface, s), x, y, z);
  EXPECT_LT((got - Eigen::Vector3d(0.002 * 0.005, 0, 0)).norm(), 1e-20);
}

// A uniform pressure on the whole surface, through make_pressure_surface3
// and the loads' step: the particles' forces, summed, and their torques.
void expect_balanced(const Body3& b, const std::vector<Eigen::Vector3d>& at) {
  StepLoad load;
  load.surface = make_pressure_surface3(b.surface, select_quads(b.surface, {}), 0, 1e5);
  ParticleStore p;
  p.dimension = 3;
  p.resize(b.sites.size());
  for (std::size_t i = 0; i < at.size(); ++i) {
    p.x[i] = at[i].x();
    p.y[i] = at[i].y();
    p.z[i] = at[i].z();
  }
  std::vector<StepLoad> loads{load};
  activate_loads(p, loads, 0, 1e-6);
  const PressureSurface& ps = loads[0].surface;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  double scale = 0;
  for (std::size_t t = 0; t < ps.targets.size(); ++t) {
    const Eigen::Vector3d f(ps.target_fx[t], ps.target_fy[t], ps.target_fz[t]);
    force += f;
    torque += at[ps.targets[t]].cross(f);
    scale += f.norm();
  }
  EXPECT_GT(scale, 0);
  EXPECT_LT(force.norm(), 1e-13 * scale);
  EXPECT_LT(torque.norm(), 1e-13 * scale * 0.02);
}

TEST(Surface3, UniformPressureGivesNoNetForceOrTorqueInAnyConfiguration) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> jitter(-3e-4, 3e-4);
  for (const Shape3& shape : shapes()) {
    const Body3 b(shape, 0.001);
    std::vector<Eigen::Vector3d> at;
    for (const Point3& s : b.sites) at.emplace_back(s.x, s.y, s.z);
    expect_balanced(b, at);
    // A large, non-affine deformation with a rotation: bend, shear and noise.
    for (Eigen::Vector3d& q : at) {
      const Eigen::Vector3d u = q;
      q = {0.01 + 1.4 * u.x() + 0.3 * u.y() + 8 * u.y() * u.y() + jitter(rng),
           -0.02 - 0.5 * u.x() + 0.7 * u.y() + 0.2 * u.z() + 12 * u.x() * u.x() + jitter(rng),
           0.1 * u.x() + 0.9 * u.z() - 6 * u.y() * u.z() + jitter(rng)};
    }
    expect_balanced(b, at);
  }
}

}  // namespace
}  // namespace mpsolid
