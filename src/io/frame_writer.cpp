#include "src/io/frame_writer.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include "src/core/region_boundary.hpp"
#include "src/io/atomic_file.hpp"
#include "src/io/hdf5_file.hpp"

namespace mpsolid {

const std::vector<XdmfField>& frame_fields(int dimension) {
  static const std::vector<XdmfField> space = {
      {"id", "Int", 4, 1},
      {"kind", "Char", 1, 1},
      {"body", "Int", 4, 1},
      {"velocity", "Float", 8, 3},
      {"rotation", "Float", 8, 3},
      {"angular_velocity", "Float", 8, 3},
      {"volumetric_strain", "Float", 8, 1},
      {"pressure", "Float", 8, 1},
      {"surface", "Char", 1, 1},
      {"normal", "Float", 8, 3},
  };
  if (dimension == 3) return space;
  static const std::vector<XdmfField> fields = {
      {"id", "Int", 4, 1},
      {"kind", "Char", 1, 1},
      {"body", "Int", 4, 1},
      {"velocity", "Float", 8, 2},
      {"rotation", "Float", 8, 1},
      {"angular_velocity", "Float", 8, 1},
      {"volumetric_strain", "Float", 8, 1},
      {"pressure", "Float", 8, 1},
      {"surface", "Char", 1, 1},
      {"normal", "Float", 8, 2},
  };
  return fields;
}

const std::vector<XdmfField>& gas_frame_fields() {
  static const std::vector<XdmfField> fields = {
      {"gas_density", "Float", 8, 1},
      {"gas_velocity", "Float", 8, 2},
      {"gas_pressure", "Float", 8, 1},
      {"gas_solid", "Char", 1, 1},
  };
  return fields;
}

struct FrameWriter::File {
  h5::File file;
  h5::Group frames;
  std::vector<std::size_t> storage_of_id;
};

namespace {
std::string frame_group(int index) {
  return fmt::format("{:06d}", index);
}

// The per-particle vectors of a space frame, in id order: `columns` arrays
// interleaved, a row per particle.
std::vector<double> rows_of(const std::vector<std::size_t>& order,
                            std::initializer_list<const std::vector<double>*> columns) {
  std::vector<double> out;
  out.reserve(order.size() * columns.size());
  for (const std::size_t i : order)
    for (const std::vector<double>* c : columns) out.push_back((*c)[i]);
  return out;
}

// A frame's fields in space. A particle is on the surface where it lacks one
// of its six nearest neighbours on the lattice; its outward normal is then
// minus the sum of its bonds' current vectors, normalised.
void write_space_fields(const SolverState& state, const std::vector<std::size_t>& order,
                        const h5::Group& group, int level) {
  const ParticleStore& p = state.particles;
  const BondTable& bonds = state.bonds;
  const std::size_t n = p.size();
  std::vector<double> rx(n, 0.0), ry(n, 0.0), rz(n, 0.0);  // the rotation vector
  std::vector<double> nx(n, 0.0), ny(n, 0.0), nz(n, 0.0);
  std::vector<std::int8_t> surface(n, 0);
  const double nearest2 = 1.01 * bonds.geometry.l0 * bonds.geometry.l0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::AngleAxisd turn(Eigen::Quaterniond(p.qw[i], p.qx[i], p.qy[i], p.qz[i]));
    const Eigen::Vector3d r = turn.angle() * turn.axis();
    rx[i] = r.x();
    ry[i] = r.y();
    rz[i] = r.z();
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
    surface[i] = 1;
    nx[i] = -now.x() / length;
    ny[i] = -now.y() / length;
    nz[i] = -now.z() / length;
  }
  std::vector<std::int8_t> surface_flag(n);
  for (std::size_t k = 0; k < n; ++k) surface_flag[k] = surface[order[k]];
  const auto scalar = [&](const std::vector<double>& field) { return rows_of(order, {&field}); };
  group.write("position", rows_of(order, {&p.x, &p.y, &p.z}), 3, level);
  group.write("velocity", rows_of(order, {&p.vx, &p.vy, &p.vz}), 3, level);
  group.write("orientation", rows_of(order, {&p.qw, &p.qx, &p.qy, &p.qz}), 4, level);
  group.write("rotation", rows_of(order, {&rx, &ry, &rz}), 3, level);
  group.write("angular_velocity", rows_of(order, {&p.omega_x, &p.omega_y, &p.omega}), 3, level);
  group.write("volumetric_strain", scalar(p.strain), 1, level);
  group.write("pressure", scalar(p.pressure), 1, level);
  group.write("surface", surface_flag, 1, level);
  group.write("normal", rows_of(order, {&nx, &ny, &nz}), 3, level);
}

std::filesystem::path sidecar_path(const std::filesystem::path& path) {
  return path.parent_path() / (path.stem().string() + ".xdmf");
}
}  // namespace

FrameWriter::FrameWriter(const std::filesystem::path& path, const SolverState& state,
                         const CaseSpec& spec, std::uint64_t run_id)
    : path_(path),
      file_(std::make_unique<File>()),
      compression_(spec.compression),
      particles_(state.particles.size()),
      dimension_(spec.dimension) {
  file_->file = h5::File::create(staging_path(path));
  file_->frames = file_->file.create_group("frames");
  file_->storage_of_id = state.particles.storage_of_id();
  std::vector<std::string> bodies;
  for (const auto& b : spec.bodies) bodies.push_back(b.name);
  file_->file.write_strings("body_names", bodies);
  file_->file.write_strings("kind_names", {"wall", "elastic", "rigid"});
  file_->file.set_attribute<double>("l0", spec.l0);
  if (spec.dimension == 3)
    file_->file.set_attribute<std::int64_t>("dimension", 3);
  else
    file_->file.set_attribute<double>("depth", spec.depth);
  file_->file.set_attribute<std::int64_t>("particles", static_cast<std::int64_t>(particles_));
  file_->file.set_attribute<std::uint64_t>("run_id", run_id);
}

FrameWriter::FrameWriter(const std::filesystem::path& path, const SolverState& state,
                         const CaseSpec& spec, std::uint64_t run_id, int keep_frames)
    : path_(path),
      file_(std::make_unique<File>()),
      compression_(spec.compression),
      particles_(state.particles.size()),
      dimension_(spec.dimension) {
  const std::filesystem::path staged = staging_path(path);
  if (!std::filesystem::exists(path))
    throw InputError(
        fmt::format("{}: missing; the checkpoint's frames cannot be continued", path.string()));
  copy_file_atomically(path, staged);
  try {
    file_->file = h5::File::open(staged, true);
    if (file_->file.attribute<std::uint64_t>("run_id") != run_id)
      throw InputError(fmt::format(
          "{} was written by another run than the checkpoint (a checkpoint from a different run "
          "or case?)",
          path.string()));
    if (file_->file.attribute<std::int64_t>("particles") != static_cast<std::int64_t>(particles_))
      throw InputError(fmt::format("{} has another particle count than the case", path.string()));
    file_->frames = file_->file.open_group("frames");
    for (const std::string& name : file_->frames.children()) {
      const int index = std::stoi(name);
      if (index >= keep_frames) file_->frames.remove(name);
    }
    for (int k = 0; k < keep_frames; ++k) {
      if (!file_->frames.has(frame_group(k)))
        throw InputError(fmt::format("{} has {} frames, the checkpoint records {}", path.string(),
                                     k, keep_frames));
      const h5::Group group = file_->frames.open_group(frame_group(k));
      frames_.push_back({"/frames/" + frame_group(k), group.attribute<double>("time")});
    }
    if (file_->file.has_attribute("gas_nx"))
      gas_grid_ = {static_cast<int>(file_->file.attribute<std::int64_t>("gas_nx")),
                   static_cast<int>(file_->file.attribute<std::int64_t>("gas_ny")),
                   file_->file.attribute<double>("gas_x0"), file_->file.attribute<double>("gas_y0"),
                   file_->file.attribute<double>("gas_cell")};
    file_->file.flush();
  } catch (const h5::Error& e) {
    throw InputError(fmt::format("{}: cannot continue it: {}", path.string(), e.what()));
  }
  file_->storage_of_id = state.particles.storage_of_id();
  first_frame_ = keep_frames;
  start_bytes_ = file_->file.size();
}

FrameWriter::~FrameWriter() = default;

std::uint64_t frames_run_id(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path))
    throw InputError(
        fmt::format("{}: missing; the checkpoint's frames cannot be continued", path.string()));
  try {
    return h5::File::open(path, false).attribute<std::uint64_t>("run_id");
  } catch (const h5::Error& e) {
    throw InputError(fmt::format("{}: cannot read it: {}", path.string(), e.what()));
  }
}

void FrameWriter::write(const SolverState& state, const CaseSpec& spec, const GasFrame& gas) {
  const ParticleStore& p = state.particles;
  const auto& order = file_->storage_of_id;
  const int index = frames_total();
  const h5::Group group = file_->frames.create_group(frame_group(index));
  group.set_attribute<std::int64_t>("step", state.step);
  group.set_attribute<double>("time", spec.time_at(state.step));

  const std::size_t n = p.size();
  auto gather = [&](const std::vector<double>& field) {
    std::vector<double> out(n);
    for (std::size_t k = 0; k < n; ++k) out[k] = field[order[k]];
    return out;
  };
  auto gather_pair = [&](const std::vector<double>& a, const std::vector<double>& b) {
    std::vector<double> out(2 * n);
    for (std::size_t k = 0; k < n; ++k) {
      out[2 * k] = a[order[k]];
      out[2 * k + 1] = b[order[k]];
    }
    return out;
  };
  std::vector<std::int32_t> id(n), body(n);
  std::vector<std::int8_t> kind(n);
  for (std::size_t k = 0; k < n; ++k) {
    id[k] = p.id[order[k]];
    body[k] = p.body[order[k]];
    kind[k] = static_cast<std::int8_t>(p.kind[order[k]]);
  }
  if (p.dimension == 3) {
    group.write("id", id, 1, compression_);
    group.write("kind", kind, 1, compression_);
    group.write("body", body, 1, compression_);
    write_space_fields(state, order, group, compression_);
    file_->file.flush();
    frames_.push_back({"/frames/" + frame_group(index), spec.time_at(state.step)});
    return;
  }
  // The surfaces' particles and their outward normals in the current state.
  if (!surfaces_built_) {
    for (std::size_t b = 0; b < spec.bodies.size(); ++b) {
      const Shape& shape = spec.bodies[b].shape;
      if (spec.bodies[b].kind == Kind::wall || !boundary_problem(shape).empty()) continue;
      surfaces_.emplace_back(state.body_ranges[b].begin,
                             build_surface(shape, fill_shape(shape, spec.l0), spec.l0));
    }
    surfaces_built_ = true;
  }
  std::vector<double> nx(n, 0.0), ny(n, 0.0), ax, ay;
  std::vector<std::int8_t> on_surface(n, 0);
  for (const auto& [first, surface] : surfaces_) {
    const std::size_t sites =
        static_cast<std::size_t>(std::max_element(surface.site.begin(), surface.site.end())[0] + 1);
    ax.assign(sites, 0.0);
    ay.assign(sites, 0.0);
    site_area_vectors(surface, p.x.data(), p.y.data(), first, ax, ay);
    for (const std::uint32_t h : surface.host) {
      const double length = std::hypot(ax[h], ay[h]);
      on_surface[first + h] = 1;
      if (length > 0) {
        nx[first + h] = ax[h] / length;
        ny[first + h] = ay[h] / length;
      }
    }
  }
  std::vector<std::int8_t> surface_flag(n);
  for (std::size_t k = 0; k < n; ++k) surface_flag[k] = on_surface[order[k]];
  const int level = compression_;
  group.write("id", id, 1, level);
  group.write("kind", kind, 1, level);
  group.write("body", body, 1, level);
  group.write("position", gather_pair(p.x, p.y), 2, level);
  group.write("velocity", gather_pair(p.vx, p.vy), 2, level);
  group.write("rotation", gather(p.theta), 1, level);
  group.write("angular_velocity", gather(p.omega), 1, level);
  group.write("volumetric_strain", gather(p.strain), 1, level);
  group.write("pressure", gather(p.pressure), 1, level);
  group.write("surface", surface_flag, 1, level);
  group.write("normal", gather_pair(nx, ny), 2, level);
  if (!gas.empty()) {
    group.write("gas_density", gas.density, 1, level);
    group.write("gas_velocity", gas.velocity, 2, level);
    group.write("gas_pressure", gas.pressure, 1, level);
    group.write("gas_solid", gas.solid, 1, level);
    if (gas_grid_.nx == 0) {
      gas_grid_ = {gas.nx, gas.ny, gas.x0, gas.y0, gas.h};
      file_->file.set_attribute<std::int64_t>("gas_nx", gas.nx);
      file_->file.set_attribute<std::int64_t>("gas_ny", gas.ny);
      file_->file.set_attribute<double>("gas_x0", gas.x0);
      file_->file.set_attribute<double>("gas_y0", gas.y0);
      file_->file.set_attribute<double>("gas_cell", gas.h);
    }
  }
  file_->file.flush();  // a crashed run keeps its frames in the staging file
  frames_.push_back({"/frames/" + frame_group(index), spec.time_at(state.step)});
}

std::uintmax_t FrameWriter::bytes_written() const {
  if (!file_->file.is_open()) return published_bytes_ - start_bytes_;
  return file_->file.size() - start_bytes_;
}

void FrameWriter::write_sidecar() const {
  write_file_atomically(
      sidecar_path(path_),
      xdmf_document(path_.filename().string(), particles_, frames_, frame_fields(dimension_),
                    gas_grid_, gas_frame_fields(), dimension_));
}

void FrameWriter::publish_copy() {
  file_->file.flush();
  copy_file_atomically(staging_path(path_), path_);
  write_sidecar();
}

void FrameWriter::publish() {
  published_bytes_ = file_->file.size();
  file_->frames = h5::Group();
  file_->file.close();
  publish_staged_file(path_);
  write_sidecar();
}

}  // namespace mpsolid
