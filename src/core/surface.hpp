#pragma once
// A body's surface (MODEL.md section 2.15): closed chains of nodes on its
// shape's boundary loops (src/core/region_boundary.hpp), each node an
// affine combination of particle positions, x_k = sum_j w_kj x_j with
// sum_j w_kj = 1, that lies exactly on the boundary in the reference
// configuration and follows the particles as the body deforms. Segment k
// joins node k to the next node of its loop, the body on its left, so its
// outward area vector is D R(x_next - x_k), R the clockwise quarter turn and
// D the depth. Forces on nodes go back to the particles with the same
// weights, so the particles get the nodes' net force and net torque exactly
// (round-off aside): a uniform pressure on a whole closed loop, whose area
// vectors telescope to zero and whose torques sum_k x_k . (x_next - x_k)
// (times the midpoint rule's 1/2) telescope too, gives the body neither, in
// any configuration.
//
// Nodes: every vertex of a straight piece, and the projection onto the
// nearest piece of every boundary site (a lattice site of the body with a
// lattice neighbour, left, right, below or above, outside it), so a straight
// face's segments add up to its length exactly and a circle's chords
// converge to its perimeter at second order. Each node's host is a site:
// the projected site, or for a vertex the nearest boundary site. Its weights
// are the linear least-squares fit over the host and its eight lattice
// neighbours in the body (exact for any affine motion).
#include <cstdint>
#include <string>
#include <vector>

#include "src/core/region.hpp"
#include "src/core/region3.hpp"

namespace mpsolid {

struct Surface {
  // Node k: its reference position, its host site, and its weights:
  // x_k = sum of weight[w] x[site[w]] over w in [offsets[k], offsets[k + 1]).
  std::vector<Point2> node_ref;
  std::vector<std::uint32_t> host;
  std::vector<std::uint32_t> offsets{0}, site;
  std::vector<double> weight;
  // Segment k runs from node k to node next[k]; face[k] is its piece's face
  // (BoundaryPiece::face: a rectangle's 0 bottom, 1 right, 2 top, 3 left).
  std::vector<std::uint32_t> next;
  std::vector<std::int32_t> face;
  std::size_t nodes() const { return host.size(); }
};

// The surface of `shape`, whose lattice sites are `sites` (fill_shape's
// order; the weights index them). Throws std::invalid_argument when the
// shape's loops are not its boundary (boundary_problem).
Surface build_surface(const Shape& shape, const std::vector<Point2>& sites, double l0);

// A part of a surface: its segments whose reference midpoints lie in a box
// (edges included), or on the side of a half-plane's line that its normal
// points to (the line included), or on a named face; all by default. In
// space the same with z (a half-space's plane; src/core/surface3.hpp).
struct SurfaceSelection {
  enum class Kind { all, face, box, half_plane };
  Kind kind = Kind::all;
  int face = -1;
  Box3 box;
  Point3 point, normal;
  bool operator==(const SurfaceSelection&) const = default;
};
std::vector<std::uint32_t> select_segments(const Surface& surface,
                                           const SurfaceSelection& selection);
// Whether the selection takes a piece of surface on `face` whose reference
// midpoint is `mid` (z = 0 in the plane), `slack` the round-off allowed at
// its edges.
bool selection_takes(const SurfaceSelection& selection, int face, Point3 mid, double slack);

// Point k of a list of affine combinations (CSR: `offsets`, the points'
// `indices` into x, y from `first`, and their `weights`): a surface's node,
// or a pressure's node over storage indices.
inline Point2 affine_point(const std::vector<std::uint32_t>& offsets,
                           const std::vector<std::uint32_t>& indices,
                           const std::vector<double>& weights, std::size_t k, const double* x,
                           const double* y, std::size_t first) {
  double px = 0, py = 0;
  for (std::uint32_t w = offsets[k]; w < offsets[k + 1]; ++w) {
    px += weights[w] * x[first + indices[w]];
    py += weights[w] * y[first + indices[w]];
  }
  return {px, py};
}

// Node k's position, its sites' positions read from x, y at `first` + site.
inline Point2 node_position(const Surface& s, std::size_t k, const double* x, const double* y,
                            std::size_t first) {
  return affine_point(s.offsets, s.site, s.weight, k, x, y, first);
}

// Each site's outward area vector per unit depth, in the configuration
// x, y (sites at `first` + site): the sum over the nodes it hosts of half
// of each neighbouring segment's R(x_next - x_k). Zero for a site that
// hosts no node. `ax`, `ay` are indexed by site.
void site_area_vectors(const Surface& s, const double* x, const double* y, std::size_t first,
                       std::vector<double>& ax, std::vector<double>& ay);
// The same from the nodes' positions `at` (every node of the surface).
void site_area_vectors_of_nodes(const Surface& s, const std::vector<Point2>& at,
                                std::vector<double>& ax, std::vector<double>& ay);

}  // namespace mpsolid
