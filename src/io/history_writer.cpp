#include "src/io/history_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>
#include <stdexcept>

#include "src/io/atomic_file.hpp"

namespace mpsolid {

std::vector<std::string> history_columns(const SolverState& state, const CaseSpec& spec) {
  const bool space = spec.dimension == 3;
  std::vector<std::string> cols = {"t",          "kinetic_energy", "strain_energy", "external_work",
                                   "momentum_x", "momentum_y"};
  // In space the momenta are vectors.
  if (space)
    cols.insert(cols.end(),
                {"momentum_z", "angular_momentum_x", "angular_momentum_y", "angular_momentum_z"});
  else
    cols.push_back("angular_momentum");
  cols.push_back("max_speed");
  if (spec.damping.coefficient > 0) cols.push_back("damping_loss");
  if (state.contact.enabled()) cols.insert(cols.end(), {"contact_energy", "contact_min_distance"});
  // A rigid body's centroid displacement and rotation from the start: in
  // space the quaternion and the angular velocity.
  const std::vector<const char*> pose =
      space ? std::vector<const char*>{".x",  ".y",  ".z",       ".qw",      ".qx",
                                       ".qy", ".qz", ".omega_x", ".omega_y", ".omega_z"}
            : std::vector<const char*>{".x", ".y", ".theta"};
  for (const RigidBody& b : state.rigid_bodies) {
    for (const char* suffix : pose) cols.push_back(b.name + suffix);
    if (b.motion.on) cols.push_back(b.name + ".work");  // its driver's
  }
  const std::vector<const char*> extent =
      space ? std::vector<const char*>{".xmin", ".xmax", ".ymin", ".ymax", ".zmin", ".zmax"}
            : std::vector<const char*>{".xmin", ".xmax", ".ymin", ".ymax"};
  const std::vector<const char*> axes =
      space ? std::vector<const char*>{".x", ".y", ".z"} : std::vector<const char*>{".x", ".y"};
  for (const BodySpec& b : spec.bodies)
    if (b.kind == Kind::elastic)
      for (const char* suffix : extent) cols.push_back(b.name + suffix);
  for (const ProbeSpec& probe : spec.probes)
    for (const char* suffix : axes) cols.push_back("probe." + probe.name + suffix);
  // A varying load's or a pressure's factor (of the step that ran last) and its work.
  for (const StepLoad& l : state.loads)
    if (!l.history.constant() || l.is_pressure())
      for (const char* suffix : {".factor", ".work"}) cols.push_back("load." + l.name + suffix);
  if (spec.gas.enabled) {
    for (const char* name :
         {"gas.steps", "gas.time", "gas.mass", "gas.energy", "gas.inflow_energy", "gas.wall_work",
          "gas.solid_work", "gas.lost_energy", "gas.coupling_error"})
      cols.push_back(name);
    for (const GasSpec::Probe& probe : spec.gas.probes)
      for (const char* suffix : {".p", ".rho"}) cols.push_back("gas." + probe.name + suffix);
  }
  return cols;
}

HistoryReadings history_readings(const SolverState& state, const CaseSpec& spec) {
  const ParticleStore& p = state.particles;
  HistoryReadings r;
  for (std::size_t b = 0; b < spec.bodies.size(); ++b)
    if (spec.bodies[b].kind == Kind::elastic)
      r.extents.push_back(extent_of(p, state.body_ranges[b]));
  for (const std::size_t i : state.probes) r.probes.push_back(position_of(p, i));
  for (const StepLoad& l : state.loads) r.load_work.push_back(load_work(p, l));
  return r;
}

std::vector<double> history_row(const SolverState& state, const CaseSpec& spec,
                                const Diagnostics& d) {
  return history_row(state, spec, d, history_readings(state, spec));
}

std::vector<double> history_row(const SolverState& state, const CaseSpec& spec,
                                const Diagnostics& d, const HistoryReadings& r) {
  const bool space = spec.dimension == 3;
  std::vector<double> row = {spec.time_at(state.step), d.kinetic_energy, d.strain_energy,
                             d.external_work,          d.momentum_x,     d.momentum_y};
  if (space) row.insert(row.end(), {d.momentum_z, d.angular_momentum_x, d.angular_momentum_y});
  row.insert(row.end(), {d.angular_momentum, d.max_speed});
  if (spec.damping.coefficient > 0) row.push_back(d.damping_loss);
  if (state.contact.enabled()) row.insert(row.end(), {d.contact_energy, d.contact_min_distance});
  for (const RigidBody& b : state.rigid_bodies) {
    row.push_back(b.xg - b.xg0);
    row.push_back(b.yg - b.yg0);
    if (space) {
      const std::array<double, 4> q = rotation_from_start(b);
      row.insert(row.end(), {b.zg - b.zg0, q[0], q[1], q[2], q[3], b.omega_x, b.omega_y, b.omega});
    } else {
      row.push_back(b.angle);
    }
    if (b.motion.on) row.push_back(b.work);
  }
  const std::size_t extent_values = space ? 6 : 4;
  for (const auto& extent : r.extents)
    row.insert(row.end(), extent.begin(), extent.begin() + static_cast<long>(extent_values));
  for (const auto& at : r.probes) row.insert(row.end(), at.begin(), at.begin() + (space ? 3 : 2));
  for (std::size_t k = 0; k < state.loads.size(); ++k) {
    const StepLoad& l = state.loads[k];
    if (!l.history.constant() || l.is_pressure())
      row.insert(row.end(), {l.active ? l.factor : 0.0, r.load_work[k]});
  }
  if (spec.gas.enabled) {
    const GasFigures& g = d.gas;
    row.insert(row.end(),
               {static_cast<double>(g.gas_steps), g.gas_time, g.mass, g.energy, g.inflow_energy,
                g.wall_work, g.solid_work, g.lost_energy, g.coupling_error});
    for (std::size_t k = 0; k < spec.gas.probes.size(); ++k)
      row.insert(row.end(), {g.probe_p[k], g.probe_rho[k]});
  }
  return row;
}

namespace {
std::string header_line(const SolverState& state, const CaseSpec& spec) {
  std::string header;
  for (const auto& c : history_columns(state, spec)) header += (header.empty() ? "" : ",") + c;
  return header + '\n';
}
}  // namespace

HistoryWriter::HistoryWriter(const std::filesystem::path& path, const SolverState& state,
                             const CaseSpec& spec)
    : path_(path) {
  file_ = std::fopen(staging_path(path).c_str(), "w");
  if (!file_) throw std::runtime_error(fmt::format("cannot write {}", staging_path(path).string()));
  const std::string header = header_line(state, spec);
  bytes_ += std::fwrite(header.data(), 1, header.size(), file_);
  file_bytes_ = bytes_;
}

HistoryWriter::HistoryWriter(const std::filesystem::path& path, const SolverState& state,
                             const CaseSpec& spec, std::uintmax_t keep_bytes)
    : path_(path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec)
    throw InputError(
        fmt::format("{}: missing; the checkpoint's history cannot be continued", path.string()));
  if (size < keep_bytes)
    throw InputError(
        fmt::format("{} has {} bytes, the checkpoint records {}", path.string(), size, keep_bytes));
  copy_file_atomically(path, staging_path(path));
  std::filesystem::resize_file(staging_path(path), keep_bytes);
  file_ = std::fopen(staging_path(path).c_str(), "r+");
  if (!file_) throw std::runtime_error(fmt::format("cannot write {}", staging_path(path).string()));
  const std::string header = header_line(state, spec);
  std::string start(header.size(), '\0');
  const std::size_t got = std::fread(start.data(), 1, start.size(), file_);
  char last = '\0';
  if (keep_bytes > 0 && std::fseek(file_, static_cast<long>(keep_bytes) - 1, SEEK_SET) == 0)
    last = static_cast<char>(std::fgetc(file_));
  if (got != header.size() || start != header || last != '\n')
    throw InputError(fmt::format(
        "{} does not hold this case's history up to the checkpoint (other columns, or cut "
        "inside a row)",
        path.string()));
  std::fseek(file_, 0, SEEK_END);
  file_bytes_ = keep_bytes;
}

HistoryWriter::~HistoryWriter() {
  if (file_) std::fclose(file_);
}

void HistoryWriter::write(const SolverState& state, const CaseSpec& spec, const Diagnostics& d,
                          const HistoryReadings& readings) {
  std::string line;
  for (double v : history_row(state, spec, d, readings)) {
    if (!line.empty()) line += ',';
    line += fmt::format("{:.17g}", v);
  }
  line += '\n';
  const std::size_t written = std::fwrite(line.data(), 1, line.size(), file_);
  bytes_ += written;
  file_bytes_ += written;
  // A crashed run keeps every frame written so far; a short write is an error.
  if (std::fflush(file_) != 0 || written != line.size())
    throw std::runtime_error(fmt::format("cannot write {}", staging_path(path_).string()));
}

void HistoryWriter::publish_copy() {
  if (std::fflush(file_) != 0)
    throw std::runtime_error(fmt::format("cannot write {}", staging_path(path_).string()));
  copy_file_atomically(staging_path(path_), path_);
}

void HistoryWriter::publish() {
  std::fclose(file_);
  file_ = nullptr;
  publish_staged_file(path_);
}

}  // namespace mpsolid
