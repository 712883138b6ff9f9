#include "src/core/frame_rows.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string_view>

#include "src/core/region_boundary.hpp"

namespace mpsolid {

std::size_t element_bytes(RowType type) {
  switch (type) {
    case RowType::f64:
      return 8;
    case RowType::i32:
      return 4;
    case RowType::i8:
      return 1;
  }
  return 0;
}

const std::vector<RowLayout>& frame_row_layout(int dimension) {
  static const std::vector<RowLayout> plane = {
      {"id", RowType::i32, 1},
      {"kind", RowType::i8, 1},
      {"body", RowType::i32, 1},
      {"position", RowType::f64, 2},
      {"velocity", RowType::f64, 2},
      {"rotation", RowType::f64, 1},
      {"angular_velocity", RowType::f64, 1},
      {"volumetric_strain", RowType::f64, 1},
      {"pressure", RowType::f64, 1},
      {"surface", RowType::i8, 1},
      {"normal", RowType::f64, 2},
  };
  static const std::vector<RowLayout> space = {
      {"id", RowType::i32, 1},
      {"kind", RowType::i8, 1},
      {"body", RowType::i32, 1},
      {"position", RowType::f64, 3},
      {"velocity", RowType::f64, 3},
      {"orientation", RowType::f64, 4},
      {"rotation", RowType::f64, 3},
      {"angular_velocity", RowType::f64, 3},
      {"volumetric_strain", RowType::f64, 1},
      {"pressure", RowType::f64, 1},
      {"surface", RowType::i8, 1},
      {"normal", RowType::f64, 3},
  };
  return dimension == 3 ? space : plane;
}

std::vector<FrameSurface> frame_surfaces(const std::vector<std::pair<Kind, const Shape*>>& bodies,
                                         const std::vector<Range>& body_ranges, double l0) {
  std::vector<FrameSurface> out;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto& [kind, shape] = bodies[b];
    if (kind == Kind::wall || !boundary_problem(*shape).empty()) continue;
    out.push_back({body_ranges.at(b).begin, build_surface(*shape, fill_shape(*shape, l0), l0)});
  }
  return out;
}

NodePositions surface_nodes(const std::vector<FrameSurface>& surfaces, const double* x,
                            const double* y,
                            const std::function<std::int64_t(std::size_t)>& local_of,
                            const std::function<bool(std::size_t)>& computes) {
  NodePositions out;
  for (const auto& [first, s] : surfaces) {
    std::vector<Point2>& at = out.emplace_back(s.nodes(), Point2{0.0, 0.0});
    for (std::size_t k = 0; k < s.nodes(); ++k) {
      if (!computes(first + s.host[k])) continue;
      // affine_point's sum, its sites found through local_of.
      double px = 0, py = 0;
      for (std::uint32_t w = s.offsets[k]; w < s.offsets[k + 1]; ++w) {
        const std::int64_t i = local_of(first + s.site[w]);
        if (i < 0) throw std::logic_error("surface_nodes: a node's site is not held here");
        px += s.weight[w] * x[i];
        py += s.weight[w] * y[i];
      }
      at[k] = {px, py};
    }
  }
  return out;
}

SurfaceMarks plane_surface_marks(const std::vector<FrameSurface>& surfaces,
                                 const NodePositions& nodes, std::size_t n,
                                 const std::function<std::int64_t(std::size_t)>& local_of) {
  SurfaceMarks marks(n);
  std::vector<double> ax, ay;
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const auto& [first, surface] = surfaces[s];
    const std::size_t sites =
        static_cast<std::size_t>(std::max_element(surface.site.begin(), surface.site.end())[0] + 1);
    ax.assign(sites, 0.0);
    ay.assign(sites, 0.0);
    site_area_vectors_of_nodes(surface, nodes.at(s), ax, ay);
    for (const std::uint32_t h : surface.host) {
      const std::int64_t i = local_of(first + h);
      if (i < 0) continue;
      const auto at = static_cast<std::size_t>(i);
      const double length = std::hypot(ax[h], ay[h]);
      marks.flag[at] = 1;
      if (length > 0) {
        marks.nx[at] = ax[h] / length;
        marks.ny[at] = ay[h] / length;
      }
    }
  }
  return marks;
}

SurfaceMarks space_surface_marks(const SolverState& state, Range marked) {
  const ParticleStore& p = state.particles;
  const BondTable& bonds = state.bonds;
  SurfaceMarks marks(p.size());
  const double nearest2 = 1.01 * bonds.geometry.l0 * bonds.geometry.l0;
  for (std::size_t i = marked.begin; i < marked.end; ++i) {
    int nearest = 0;
    Eigen::Vector3d now = Eigen::Vector3d::Zero();
    for (std::uint32_t b = bonds.begin(i); b < bonds.end(i); ++b) {
      const std::size_t j = bonds.neighbor[b];
      const Eigen::Vector3d r0(bonds.r0x[b], bonds.r0y[b], bonds.r0z[b]);
      nearest += r0.squaredNorm() < nearest2;
      now += Eigen::Vector3d(p.x[j] - p.x[i], p.y[j] - p.y[i], p.z[j] - p.z[i]);
    }
    const double length = now.norm();
    if (nearest >= 6 || length == 0) continue;
    marks.flag[i] = 1;
    marks.nx[i] = -now.x() / length;
    marks.ny[i] = -now.y() / length;
    marks.nz[i] = -now.z() / length;
  }
  return marks;
}

namespace {
// The members' rows of `columns` interleaved.
std::vector<double> rows_of(const std::vector<std::size_t>& members,
                            std::initializer_list<const std::vector<double>*> columns) {
  std::vector<double> out;
  out.reserve(members.size() * columns.size());
  for (const std::size_t i : members)
    for (const std::vector<double>* c : columns) out.push_back((*c)[i]);
  return out;
}

template <class T, class Read>
std::vector<T> each(const std::vector<std::size_t>& members, Read read) {
  std::vector<T> out(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) out[k] = read(members[k]);
  return out;
}

// In space a frame's rotation is the rotation vector (axis times angle) of
// the orientation quaternion.
std::vector<double> rotation_vectors(const ParticleStore& p,
                                     const std::vector<std::size_t>& members) {
  std::vector<double> out;
  out.reserve(3 * members.size());
  for (const std::size_t i : members) {
    const Eigen::AngleAxisd turn(Eigen::Quaterniond(p.qw[i], p.qx[i], p.qy[i], p.qz[i]));
    const Eigen::Vector3d r = turn.angle() * turn.axis();
    out.insert(out.end(), {r.x(), r.y(), r.z()});
  }
  return out;
}
}  // namespace

RowValues frame_rows(const RowLayout& field, const ParticleStore& p,
                     const std::vector<std::size_t>& members, const SurfaceMarks& marks) {
  const std::string_view name = field.name;
  const bool space = p.dimension == 3;
  if (name == "id") return each<std::int32_t>(members, [&](std::size_t i) { return p.id[i]; });
  if (name == "kind")
    return each<std::int8_t>(members,
                             [&](std::size_t i) { return static_cast<std::int8_t>(p.kind[i]); });
  if (name == "body") return each<std::int32_t>(members, [&](std::size_t i) { return p.body[i]; });
  if (name == "position")
    return space ? rows_of(members, {&p.x, &p.y, &p.z}) : rows_of(members, {&p.x, &p.y});
  if (name == "velocity")
    return space ? rows_of(members, {&p.vx, &p.vy, &p.vz}) : rows_of(members, {&p.vx, &p.vy});
  if (name == "orientation") return rows_of(members, {&p.qw, &p.qx, &p.qy, &p.qz});
  if (name == "rotation")
    return space ? rotation_vectors(p, members) : rows_of(members, {&p.theta});
  if (name == "angular_velocity")
    return space ? rows_of(members, {&p.omega_x, &p.omega_y, &p.omega})
                 : rows_of(members, {&p.omega});
  if (name == "volumetric_strain") return rows_of(members, {&p.strain});
  if (name == "pressure") return rows_of(members, {&p.pressure});
  if (name == "surface")
    return each<std::int8_t>(members, [&](std::size_t i) { return marks.flag[i]; });
  if (name == "normal")
    return space ? rows_of(members, {&marks.nx, &marks.ny, &marks.nz})
                 : rows_of(members, {&marks.nx, &marks.ny});
  throw std::logic_error("frame_rows: no field " + std::string(name));
}

SurfaceMarks whole_surface_marks(const SolverState& state,
                                 const std::vector<FrameSurface>& surfaces) {
  const ParticleStore& p = state.particles;
  const std::size_t n = p.size();
  if (p.dimension == 3) return space_surface_marks(state, {0, n});
  const auto same = [](std::size_t g) { return static_cast<std::int64_t>(g); };
  return plane_surface_marks(
      surfaces,
      surface_nodes(surfaces, p.x.data(), p.y.data(), same, [](std::size_t) { return true; }), n,
      same);
}

}  // namespace mpsolid
