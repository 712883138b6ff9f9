#include "src/core/surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "src/core/region_boundary.hpp"

namespace mpsolid {

namespace {
// The body's sites by lattice index.
class SiteIndex {
 public:
  SiteIndex(const std::vector<Point2>& sites, double l0) : l0_(l0) {
    index_.reserve(sites.size());
    for (std::size_t i = 0; i < sites.size(); ++i)
      index_.emplace(key(lattice(sites[i].x), lattice(sites[i].y)), static_cast<std::uint32_t>(i));
  }
  std::int64_t lattice(double x) const { return std::llround(x / l0_ - 0.5); }
  // The site at lattice index (k, m), or -1.
  std::int64_t at(std::int64_t k, std::int64_t m) const {
    const auto it = index_.find(key(k, m));
    return it == index_.end() ? std::int64_t{-1} : std::int64_t{it->second};
  }

 private:
  static std::int64_t key(std::int64_t k, std::int64_t m) {
    return k * (std::int64_t{1} << 32) + (m & 0xffffffff);
  }
  double l0_;
  std::unordered_map<std::int64_t, std::uint32_t> index_;
};

struct Node {
  std::size_t piece;
  double t;
  std::uint32_t host;
};

double distance(Point2 a, Point2 b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

// The weights of a node at `at` hosted by site h: the least-norm weights w_j
// that sum to one and reproduce X_k = sum_j w_j X_j, over h and its eight
// lattice neighbours in the body (an affine least-squares fit through all
// of them, evaluated at X_k). With d_j = X_j - X_h, c their mean and
// C = sum_j (d_j - c)(d_j - c)^T: w_j = 1/n + (d_j - c)^T C^+ (X_k - X_h - c).
// A fit anchored at h instead (h's weight near 1.5, its neighbours' negative)
// pushes hard on the near-surface modes that F does not see: the Lame
// cylinder and the squeezed disk come out softer with it (docs/MODEL.md).
// The pseudo-inverse keeps a row of sites one site thick well defined.
void add_weights(Surface& s, const std::vector<Point2>& sites, const SiteIndex& index,
                 std::uint32_t h, Point2 at) {
  const Point2 xh = sites[h];
  const std::int64_t k = index.lattice(xh.x), m = index.lattice(xh.y);
  std::vector<std::uint32_t> near{h};
  for (std::int64_t dm = -1; dm <= 1; ++dm)
    for (std::int64_t dk = -1; dk <= 1; ++dk)
      if (dk != 0 || dm != 0)
        if (const std::int64_t j = index.at(k + dk, m + dm); j >= 0)
          near.push_back(static_cast<std::uint32_t>(j));
  const double n = static_cast<double>(near.size());
  double cx = 0, cy = 0;
  for (const std::uint32_t j : near) {
    cx += sites[j].x - xh.x;
    cy += sites[j].y - xh.y;
  }
  cx /= n;
  cy /= n;
  double a11 = 0, a12 = 0, a22 = 0;
  for (const std::uint32_t j : near) {
    const double ex = sites[j].x - xh.x - cx, ey = sites[j].y - xh.y - cy;
    a11 += ex * ex;
    a12 += ex * ey;
    a22 += ey * ey;
  }
  // C^+ (X_k - X_h - c), as (gx, gy).
  const double rx = at.x - xh.x - cx, ry = at.y - xh.y - cy;
  double gx = 0, gy = 0;
  const double det = a11 * a22 - a12 * a12, trace = a11 + a22;
  if (det > 1e-9 * trace * trace) {
    gx = (a22 * rx - a12 * ry) / det;
    gy = (a11 * ry - a12 * rx) / det;
  } else if (trace > 0) {
    // Rank one: C = trace u u^T.
    const double norm = std::hypot(a11, a12) > 0 ? std::hypot(a11, a12) : std::hypot(a12, a22);
    const double ux = (a11 > 0 ? a11 : a12) / norm, uy = (a11 > 0 ? a12 : a22) / norm;
    const double along = (ux * rx + uy * ry) / trace;
    gx = along * ux;
    gy = along * uy;
  }
  // The host first (it says which part positions the node).
  for (const std::uint32_t j : near) {
    const double w = 1.0 / n + (sites[j].x - xh.x - cx) * gx + (sites[j].y - xh.y - cy) * gy;
    if (w == 0.0 && j != h) continue;
    s.site.push_back(j);
    s.weight.push_back(w);
  }
  s.offsets.push_back(static_cast<std::uint32_t>(s.site.size()));
}
}  // namespace

Surface build_surface(const Shape& shape, const std::vector<Point2>& sites, double l0) {
  if (const std::string problem = boundary_problem(shape); !problem.empty())
    throw std::invalid_argument("the shape's surface is not a set of separate loops: " + problem);
  const SiteIndex index(sites, l0);
  std::vector<std::uint32_t> boundary;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    const std::int64_t k = index.lattice(sites[i].x), m = index.lattice(sites[i].y);
    if (index.at(k - 1, m) < 0 || index.at(k + 1, m) < 0 || index.at(k, m - 1) < 0 ||
        index.at(k, m + 1) < 0)
      boundary.push_back(static_cast<std::uint32_t>(i));
  }

  // Every piece of every loop, numbered in loop order.
  const std::vector<BoundaryLoop> loops = shape_boundary(shape);
  std::vector<BoundaryPiece> pieces;
  std::vector<std::size_t> loop_start;
  for (const BoundaryLoop& loop : loops) {
    loop_start.push_back(pieces.size());
    pieces.insert(pieces.end(), loop.begin(), loop.end());
  }
  loop_start.push_back(pieces.size());

  // Each boundary site projected onto its nearest piece (or pieces, at a
  // corner equally near two), where the projection falls inside the piece.
  std::vector<Node> nodes;
  const double tie = 1e-9 * l0, inside = 1e-9;
  std::vector<double> t(pieces.size()), d(pieces.size());
  for (const std::uint32_t i : boundary) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      t[p] = piece_parameter(pieces[p], sites[i]);
      d[p] = distance(piece_point(pieces[p], t[p]), sites[i]);
      nearest = std::min(nearest, d[p]);
    }
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      const bool interior =
          pieces[p].kind == BoundaryPiece::Kind::ellipse || (t[p] > inside && t[p] < 1.0 - inside);
      if (d[p] <= nearest + tie && interior) nodes.push_back({p, t[p], i});
    }
  }
  // The nearest boundary site to a point (the lowest index on a tie).
  const auto nearest_site = [&](Point2 at) {
    std::uint32_t best = boundary.front();
    double best_d = std::numeric_limits<double>::infinity();
    for (const std::uint32_t i : boundary)
      if (const double di = distance(sites[i], at); di < best_d) {
        best = i;
        best_d = di;
      }
    return best;
  };
  std::vector<std::size_t> per_loop(loops.size(), 0);
  for (const Node& n : nodes)
    ++per_loop[std::upper_bound(loop_start.begin(), loop_start.end(), n.piece) -
               loop_start.begin() - 1];
  for (std::size_t p = 0; p < pieces.size(); ++p)
    if (pieces[p].kind == BoundaryPiece::Kind::edge)
      nodes.push_back({p, 0.0, nearest_site(pieces[p].a)});
  // A curve too small to have boundary sites of its own still gets a polygon.
  for (std::size_t l = 0; l < loops.size(); ++l)
    if (loops[l].size() == 1 && loops[l][0].kind == BoundaryPiece::Kind::ellipse && per_loop[l] < 8)
      for (int j = 0; j < 8; ++j) {
        const double tj = j / 8.0;
        nodes.push_back({loop_start[l], tj, nearest_site(piece_point(pieces[loop_start[l]], tj))});
      }

  // Along each loop in order; one node per point.
  std::sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) {
    return a.piece != b.piece ? a.piece < b.piece : a.t != b.t ? a.t < b.t : a.host < b.host;
  });
  nodes.erase(
      std::unique(nodes.begin(), nodes.end(),
                  [](const Node& a, const Node& b) { return a.piece == b.piece && a.t == b.t; }),
      nodes.end());

  Surface s;
  std::size_t first_of_loop = 0;
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const BoundaryPiece& piece = pieces[nodes[n].piece];
    const Point2 at = piece_point(piece, nodes[n].t);
    s.node_ref.push_back(at);
    s.host.push_back(nodes[n].host);
    add_weights(s, sites, index, nodes[n].host, at);
    s.face.push_back(piece.face);
    const auto loop_of = [&](std::size_t piece_index) {
      return std::upper_bound(loop_start.begin(), loop_start.end(), piece_index) -
             loop_start.begin();
    };
    const bool last_of_loop =
        n + 1 == nodes.size() || loop_of(nodes[n + 1].piece) != loop_of(nodes[n].piece);
    s.next.push_back(static_cast<std::uint32_t>(last_of_loop ? first_of_loop : n + 1));
    if (last_of_loop) first_of_loop = n + 1;
  }
  return s;
}

bool selection_takes(const SurfaceSelection& selection, int face, Point3 mid, double slack) {
  switch (selection.kind) {
    case SurfaceSelection::Kind::all:
      return true;
    case SurfaceSelection::Kind::face:
      return face == selection.face;
    case SurfaceSelection::Kind::box: {
      const Box3& b = selection.box;
      return mid.x >= b.lo.x - slack && mid.x <= b.hi.x + slack && mid.y >= b.lo.y - slack &&
             mid.y <= b.hi.y + slack && mid.z >= b.lo.z - slack && mid.z <= b.hi.z + slack;
    }
    case SurfaceSelection::Kind::half_plane: {
      // A normal in the plane keeps the plane's arithmetic (and its bits).
      const Point3 n = selection.normal, p = selection.point;
      const double length = n.z == 0 ? std::hypot(n.x, n.y) : std::hypot(n.x, n.y, n.z);
      const double plane = (mid.x - p.x) * n.x + (mid.y - p.y) * n.y;
      return (n.z == 0 ? plane : plane + (mid.z - p.z) * n.z) >= -slack * length;
    }
  }
  return false;
}

std::vector<std::uint32_t> select_segments(const Surface& surface,
                                           const SurfaceSelection& selection) {
  std::vector<std::uint32_t> chosen;
  for (std::size_t k = 0; k < surface.nodes(); ++k) {
    const Point2 a = surface.node_ref[k], b = surface.node_ref[surface.next[k]];
    // A midpoint on the selection's edge counts, give or take round-off in
    // the nodes (a circle's nodes come from sines and cosines), so a
    // symmetric selection of a symmetric body stays symmetric.
    const double slack = 1e-9 * std::hypot(b.x - a.x, b.y - a.y);
    if (selection_takes(selection, surface.face[k], {0.5 * (a.x + b.x), 0.5 * (a.y + b.y), 0.0},
                        slack))
      chosen.push_back(static_cast<std::uint32_t>(k));
  }
  return chosen;
}

void site_area_vectors_of_nodes(const Surface& s, const std::vector<Point2>& at,
                                std::vector<double>& ax, std::vector<double>& ay) {
  std::fill(ax.begin(), ax.end(), 0.0);
  std::fill(ay.begin(), ay.end(), 0.0);
  for (std::size_t k = 0; k < s.nodes(); ++k) {
    const std::size_t n = s.next[k];
    // Half of R(x_n - x_k), R the clockwise quarter turn, to each end.
    const double hx = 0.5 * (at[n].y - at[k].y), hy = -0.5 * (at[n].x - at[k].x);
    ax[s.host[k]] += hx;
    ay[s.host[k]] += hy;
    ax[s.host[n]] += hx;
    ay[s.host[n]] += hy;
  }
}

void site_area_vectors(const Surface& s, const double* x, const double* y, std::size_t first,
                       std::vector<double>& ax, std::vector<double>& ay) {
  std::vector<Point2> at(s.nodes());
  for (std::size_t k = 0; k < s.nodes(); ++k) at[k] = node_position(s, k, x, y, first);
  site_area_vectors_of_nodes(s, at, ax, ay);
}

}  // namespace mpsolid
