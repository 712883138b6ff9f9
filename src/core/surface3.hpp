#pragma once
// A 3D body's surface (MODEL.md section 10): a closed mesh of quadrilaterals
// whose nodes lie on the shape's surface (src/core/region3_boundary.hpp),
// each node an affine combination of particle positions, x_k = sum_j w_kj x_j
// with sum_j w_kj = 1, so the mesh follows the particles as the body
// deforms, as the plane's surfaces do (src/core/surface.hpp).
//
// The mesh is the boundary of the body's lattice cells (the cubes of side
// l0 about its sites): one quadrilateral per cell face that no other cell of
// the body shares, its corners counter-clockwise seen from outside. Each
// corner is then moved to the point of the shape's surface nearest it. Any
// corner positions leave the mesh closed, so a uniform pressure on all of
// it gives the body neither force nor torque in any configuration
// (round-off aside); and a part's net force is the pressure times the
// vector area its boundary loop spans, which the moved corners put on the
// shape's surface. A box whose faces lie on cell faces gets them exactly.
//
// A quadrilateral is split into four triangles through its centre (the mean
// of its corners), so no diagonal is preferred; each triangle's force goes a
// third to each of its corners, the centre's a quarter to each corner. Each
// node's host is the body's site nearest it among the cells at its corner;
// its weights are the linear least-squares fit over the host and its 26
// lattice neighbours in the body (exact for any affine motion).
#include <cstdint>
#include <vector>

#include "src/core/region3.hpp"
#include "src/core/surface.hpp"

namespace mpsolid {

struct Surface3 {
  // Node k: its reference position, its host site, and its weights:
  // x_k = sum of weight[w] x[site[w]] over w in [offsets[k], offsets[k + 1]).
  std::vector<Point3> node_ref;
  std::vector<std::uint32_t> host;
  std::vector<std::uint32_t> offsets{0}, site;
  std::vector<double> weight;
  // Quadrilateral q's corners are corner[4 q .. 4 q + 3]; face[q] the named
  // face of the shape's surface nearest its centre (src/core/region3_boundary.hpp).
  std::vector<std::uint32_t> corner;
  std::vector<std::int32_t> face;
  std::size_t nodes() const { return host.size(); }
  std::size_t quads() const { return face.size(); }
};

// The surface of `shape`, whose lattice sites are `sites` (fill_shape3's
// order; the weights index them).
Surface3 build_surface3(const Shape3& shape, const std::vector<Point3>& sites, double l0);

// Its quadrilaterals whose reference centres the selection takes (as
// select_segments in the plane, with z).
std::vector<std::uint32_t> select_quads(const Surface3& surface, const SurfaceSelection& selection);

// The outward area vector 1/2 (p - m) x (q - m) of the triangle from the
// centre m of a quadrilateral to its edge from p to q.
inline void triangle_area_vector(const double* m, const double* p, const double* q, double* a) {
  const double u[3] = {p[0] - m[0], p[1] - m[1], p[2] - m[2]};
  const double v[3] = {q[0] - m[0], q[1] - m[1], q[2] - m[2]};
  a[0] = 0.5 * (u[1] * v[2] - u[2] * v[1]);
  a[1] = 0.5 * (u[2] * v[0] - u[0] * v[2]);
  a[2] = 0.5 * (u[0] * v[1] - u[1] * v[0]);
}

// Nodes' positions or forces, one array per axis.
struct NodeXYZ {
  const double *x, *y, *z;
};
struct NodeForces {
  double *x, *y, *z;
};

// Adds to each node `scale` times its share of the outward area vectors of
// the quadrilaterals whose corners are `corner` (four per quadrilateral,
// indices of the nodes at `at`): a pressure's forces with scale = -p, a
// node's area vector with scale = 1.
void add_node_area_vectors(const std::vector<std::uint32_t>& corner, const NodeXYZ& at,
                           double scale, NodeForces out);

// The volume the closed mesh of quadrilaterals `corner` encloses, its nodes
// at `at` (`nodes` of them): 1/3 of the sum of x_k . a_k, a_k node k's
// share of the area vectors, exactly the triangles' sum of centroid . area.
double enclosed_volume(const std::vector<std::uint32_t>& corner, const NodeXYZ& at,
                       std::size_t nodes);

}  // namespace mpsolid
