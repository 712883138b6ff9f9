#include "src/core/surface3.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "src/core/region3_boundary.hpp"

namespace mpsolid {

namespace {
using Index3 = std::array<std::int64_t, 3>;

// Lattice indices (of sites or of cell corners) as one key.
std::int64_t key(const Index3& k) {
  constexpr std::int64_t kBias = std::int64_t{1} << 20, kMask = (std::int64_t{1} << 21) - 1;
  for (const std::int64_t v : k)
    if (v <= -kBias || v >= kBias)
      throw std::invalid_argument("a body spans more than a million lattice spacings");
  return ((k[0] + kBias) & kMask) | (((k[1] + kBias) & kMask) << 21) |
         (((k[2] + kBias) & kMask) << 42);
}

// The body's sites by lattice index: site (k, m, n) at ((k + 1/2) l0, ...).
class SiteIndex3 {
 public:
  SiteIndex3(const std::vector<Point3>& sites, double l0) : l0_(l0) {
    index_.reserve(sites.size());
    for (std::size_t i = 0; i < sites.size(); ++i)
      index_.emplace(key(lattice(sites[i])), static_cast<std::uint32_t>(i));
  }
  Index3 lattice(Point3 p) const {
    return {std::llround(p.x / l0_ - 0.5), std::llround(p.y / l0_ - 0.5),
            std::llround(p.z / l0_ - 0.5)};
  }
  // The site at lattice index k, or -1.
  std::int64_t at(const Index3& k) const {
    const auto it = index_.find(key(k));
    return it == index_.end() ? std::int64_t{-1} : std::int64_t{it->second};
  }

 private:
  double l0_;
  std::unordered_map<std::int64_t, std::uint32_t> index_;
};

Eigen::Vector3d vec(Point3 p) {
  return {p.x, p.y, p.z};
}

// Whether two lattice indices are neighbours (or the same).
bool adjacent(const Index3& a, const Index3& b) {
  return std::abs(a[0] - b[0]) <= 1 && std::abs(a[1] - b[1]) <= 1 && std::abs(a[2] - b[2]) <= 1;
}

// The weights of a node at `at` hosted by site h: the least-norm weights
// that sum to one and reproduce the node's position, over h and its 26
// lattice neighbours in the body that neighbour each of `tied` too (the
// sites as near the node as h: on a flat face, the four behind a cell
// corner, so the stencil is symmetric about the node and needs no
// tie-break) (the plane's fit, src/core/surface.cpp, with a 3 x 3 moment
// matrix): with d_j = X_j - X_h, c their mean and C = sum_j (d_j - c)
// (d_j - c)^T, w_j = 1/n + (d_j - c)^T C^+ (X_k - X_h - c). The
// pseudo-inverse keeps a sheet or a line of sites well defined.
void add_weights(Surface3& s, const std::vector<Point3>& sites, const SiteIndex3& index,
                 std::uint32_t h, const std::vector<std::uint32_t>& tied, Point3 at) {
  const Eigen::Vector3d xh = vec(sites[h]);
  const Index3 k = index.lattice(sites[h]);
  std::vector<Index3> tied_at;
  for (const std::uint32_t t : tied) tied_at.push_back(index.lattice(sites[t]));
  std::vector<std::uint32_t> near{h};
  for (std::int64_t dn = -1; dn <= 1; ++dn)
    for (std::int64_t dm = -1; dm <= 1; ++dm)
      for (std::int64_t dk = -1; dk <= 1; ++dk) {
        const Index3 m{k[0] + dk, k[1] + dm, k[2] + dn};
        if (dk == 0 && dm == 0 && dn == 0) continue;
        const std::int64_t j = index.at(m);
        if (j >= 0 && std::all_of(tied_at.begin(), tied_at.end(),
                                  [&](const Index3& t) { return adjacent(m, t); }))
          near.push_back(static_cast<std::uint32_t>(j));
      }
  const double n = static_cast<double>(near.size());
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const std::uint32_t j : near) c += vec(sites[j]) - xh;
  c /= n;
  Eigen::Matrix3d moments = Eigen::Matrix3d::Zero();
  for (const std::uint32_t j : near) {
    const Eigen::Vector3d e = vec(sites[j]) - xh - c;
    moments += e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(moments);
  const Eigen::Vector3d values = eigen.eigenvalues();
  const double cutoff = 1e-9 * values.maxCoeff();
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    if (values[a] > cutoff) inverse[a] = 1.0 / values[a];
  const Eigen::Matrix3d& axes = eigen.eigenvectors();
  const Eigen::Vector3d g = axes * inverse.asDiagonal() * axes.transpose() * (vec(at) - xh - c);
  // The host first (it says which part positions the node).
  for (const std::uint32_t j : near) {
    const double w = 1.0 / n + (vec(sites[j]) - xh - c).dot(g);
    if (w == 0.0 && j != h) continue;
    s.site.push_back(j);
    s.weight.push_back(w);
  }
  s.offsets.push_back(static_cast<std::uint32_t>(s.site.size()));
}

Point3 mean(const std::vector<Point3>& points, const std::uint32_t* corners) {
  Point3 m;
  for (int c = 0; c < 4; ++c) {
    m.x += 0.25 * points[corners[c]].x;
    m.y += 0.25 * points[corners[c]].y;
    m.z += 0.25 * points[corners[c]].z;
  }
  return m;
}

// How far to move p along direction `side` e_axis (side = +-1) to cross the
// shape's surface from inside to outside: the crossing nearest p within
// l0 either way (found on a grid of l0 / 4, then by bisection), if any.
std::optional<double> crossing(const Shape3& shape, Point3 p, int axis, int side, double l0) {
  const auto inside = [&](double t) {
    Point3 q = p;
    (axis == 0 ? q.x : axis == 1 ? q.y : q.z) += side * t;
    return shape3_contains(shape, q);
  };
  std::optional<double> best;
  for (int k = -4; k < 4; ++k) {
    double lo = k * l0 / 4, hi = (k + 1) * l0 / 4;
    if (!inside(lo) || inside(hi)) continue;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      (inside(mid) ? lo : hi) = mid;
    }
    const double t = 0.5 * (lo + hi);
    if (!best || std::abs(t) < std::abs(*best)) best = t;
  }
  return best;
}

// A node's place on the shape's surface, from its lattice corner: moved
// along each axis on which the faces meeting there all face one way, to
// where that line crosses the surface, then to the nearest point of the
// surface (a curved surface's). The line runs through the corner (a hair
// inside along the other axes that move, so a line along a half-open
// region's far face still meets it), or where that one misses the body,
// through the body's sites at the corner, `inside` (their crossings'
// mean): so a box's edges and corners go to the box's, whether they lie on
// the cells' faces or not.
Point3 place_corner(const Shape3& shape, Point3 corner, std::uint8_t normals,
                    const std::vector<Point3>& inside, double l0) {
  int side[3] = {0, 0, 0};
  for (int axis = 0; axis < 3; ++axis) {
    const bool low = normals & (1u << (2 * axis)), high = normals & (1u << (2 * axis + 1));
    if (low != high) side[axis] = high ? 1 : -1;
  }
  const double hair = 1e-7 * l0;
  const double c[3] = {corner.x, corner.y, corner.z};
  double at[3] = {corner.x, corner.y, corner.z};
  for (int axis = 0; axis < 3; ++axis) {
    if (side[axis] == 0) continue;
    double start[3];
    for (int a = 0; a < 3; ++a) start[a] = a == axis ? c[a] : c[a] - hair * side[a];
    std::optional<double> t = crossing(shape, {start[0], start[1], start[2]}, axis, side[axis], l0);
    if (!t) {
      // The mean over the sites' lines, so a symmetric body stays symmetric.
      double sum = 0;
      int found = 0;
      for (Point3 line : inside) {
        (axis == 0 ? line.x : axis == 1 ? line.y : line.z) = c[axis];
        if (const std::optional<double> along = crossing(shape, line, axis, side[axis], l0)) {
          sum += *along;
          ++found;
        }
      }
      if (found > 0) t = sum / found;
    }
    if (t) at[axis] += side[axis] * *t;
  }
  return nearest_shape3_surface_point(shape, {at[0], at[1], at[2]}).at;
}
}  // namespace

Surface3 build_surface3(const Shape3& shape, const std::vector<Point3>& sites, double l0) {
  const SiteIndex3 index(sites, l0);
  // The cells' faces that no other cell shares, each as its four lattice
  // corners (the corner at (c_x l0, c_y l0, c_z l0)) counter-clockwise about
  // its outward normal; each corner numbered the first time a face reaches
  // it, with the outward normals of the faces that meet at it (one bit per
  // direction: axis a's low side 2 a, its high side 2 a + 1).
  std::vector<std::uint32_t> corner_of_face;
  std::vector<Index3> corners;
  std::vector<std::uint8_t> normals;
  std::unordered_map<std::int64_t, std::uint32_t> node_of_corner;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const Index3 k = index.lattice(sites[i]);
    for (int axis = 0; axis < 3; ++axis)
      for (const int side : {-1, 1}) {
        Index3 beside = k;
        beside[axis] += side;
        if (index.at(beside) >= 0) continue;
        // The other two axes b, c cyclic after the axis, so e_b x e_c = e_axis.
        const int b = (axis + 1) % 3, c = (axis + 2) % 3;
        constexpr int kAround[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        std::uint32_t face[4];
        for (int q = 0; q < 4; ++q) {
          Index3 at = k;
          at[axis] += side > 0 ? 1 : 0;
          at[b] += kAround[q][0];
          at[c] += kAround[q][1];
          const auto [it, added] =
              node_of_corner.emplace(key(at), static_cast<std::uint32_t>(corners.size()));
          if (added) {
            corners.push_back(at);
            normals.push_back(0);
          }
          normals[it->second] |= static_cast<std::uint8_t>(1u << (2 * axis + (side > 0 ? 1 : 0)));
          face[side > 0 ? q : 3 - q] = it->second;
        }
        corner_of_face.insert(corner_of_face.end(), face, face + 4);
      }
  }

  Surface3 s;
  for (std::size_t n = 0; n < corners.size(); ++n) {
    const Index3& c = corners[n];
    // The body's sites whose cells share the corner.
    std::vector<std::uint32_t> around;
    std::vector<Point3> inside;
    for (int b = 0; b < 8; ++b) {
      const Index3 k{c[0] - 1 + (b & 1), c[1] - 1 + ((b >> 1) & 1), c[2] - 1 + ((b >> 2) & 1)};
      if (const std::int64_t j = index.at(k); j >= 0) {
        around.push_back(static_cast<std::uint32_t>(j));
        inside.push_back(sites[static_cast<std::size_t>(j)]);
      }
    }
    const Point3 at = place_corner(shape,
                                   {static_cast<double>(c[0]) * l0, static_cast<double>(c[1]) * l0,
                                    static_cast<double>(c[2]) * l0},
                                   normals[n], inside, l0);
    // Host: the nearest of them (the first, where several are as near).
    std::uint32_t host = 0;
    double best = std::numeric_limits<double>::infinity();
    for (const std::uint32_t j : around) {
      const double d = (vec(sites[j]) - vec(at)).norm();
      if (d < best) {
        best = d;
        host = static_cast<std::uint32_t>(j);
      }
    }
    std::vector<std::uint32_t> tied;
    for (const std::uint32_t j : around)
      if ((vec(sites[j]) - vec(at)).norm() <= best + 1e-7 * l0) tied.push_back(j);
    s.node_ref.push_back(at);
    s.host.push_back(host);
    add_weights(s, sites, index, host, tied, at);
  }
  s.corner = std::move(corner_of_face);
  for (std::size_t q = 0; 4 * q < s.corner.size(); ++q)
    s.face.push_back(nearest_shape3_surface_point(shape, mean(s.node_ref, &s.corner[4 * q])).face);
  return s;
}

std::vector<std::uint32_t> select_quads(const Surface3& surface,
                                        const SurfaceSelection& selection) {
  std::vector<std::uint32_t> chosen;
  for (std::size_t q = 0; q < surface.quads(); ++q) {
    const std::uint32_t* corners = &surface.corner[4 * q];
    const Point3 a = surface.node_ref[corners[0]], c = surface.node_ref[corners[2]];
    const double slack = 1e-9 * std::hypot(c.x - a.x, c.y - a.y, c.z - a.z);
    if (selection_takes(selection, surface.face[q], mean(surface.node_ref, corners), slack))
      chosen.push_back(static_cast<std::uint32_t>(q));
  }
  return chosen;
}

void add_node_area_vectors(const std::vector<std::uint32_t>& corner, const NodeXYZ& at,
                           double scale, NodeForces out) {
  for (std::size_t q = 0; 4 * q < corner.size(); ++q) {
    const std::uint32_t* k = &corner[4 * q];
    double p[4][3], m[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c) {
      p[c][0] = at.x[k[c]];
      p[c][1] = at.y[k[c]];
      p[c][2] = at.z[k[c]];
      for (int a = 0; a < 3; ++a) m[a] += 0.25 * p[c][a];
    }
    // A third of each triangle to its two corners and to the centre; the
    // centre's total a quarter to each corner.
    double share[4][3] = {}, centre[3] = {0, 0, 0};
    for (int c = 0; c < 4; ++c) {
      const int d = (c + 1) % 4;
      double area[3];
      triangle_area_vector(m, p[c], p[d], area);
      for (int a = 0; a < 3; ++a) {
        const double third = scale * area[a] / 3.0;
        share[c][a] += third;
        share[d][a] += third;
        centre[a] += third;
      }
    }
    for (int c = 0; c < 4; ++c) {
      out.x[k[c]] += share[c][0] + 0.25 * centre[0];
      out.y[k[c]] += share[c][1] + 0.25 * centre[1];
      out.z[k[c]] += share[c][2] + 0.25 * centre[2];
    }
  }
}

double enclosed_volume(const std::vector<std::uint32_t>& corner, const NodeXYZ& at,
                       std::size_t nodes) {
  std::vector<double> ax(nodes, 0.0), ay(nodes, 0.0), az(nodes, 0.0);
  add_node_area_vectors(corner, at, 1.0, {ax.data(), ay.data(), az.data()});
  double v = 0;
  for (std::size_t k = 0; k < nodes; ++k) v += at.x[k] * ax[k] + at.y[k] * ay[k] + at.z[k] * az[k];
  return v / 3;
}

}  // namespace mpsolid
