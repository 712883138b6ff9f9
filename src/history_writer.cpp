#include "src/history_writer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "src/atomic_file.hpp"

namespace mpsolid {

std::vector<std::string> history_columns(const Simulation& sim) {
  std::vector<std::string> cols = {
      "t",          "kinetic_energy", "strain_energy",    "external_work",
      "momentum_x", "momentum_y",     "angular_momentum", "max_speed"};
  for (const RigidBody& b : sim.state().rigid_bodies)
    for (const char* suffix : {".x", ".y", ".theta"}) cols.push_back(b.name + suffix);
  for (const BodySpec& b : sim.spec().bodies)
    if (b.kind == Kind::elastic)
      for (const char* suffix : {".xmin", ".xmax", ".ymin", ".ymax"})
        cols.push_back(b.name + suffix);
  return cols;
}

std::vector<double> history_row(const Simulation& sim, const Diagnostics& d) {
  std::vector<double> row = {sim.time(),   d.kinetic_energy, d.strain_energy,    d.external_work,
                             d.momentum_x, d.momentum_y,     d.angular_momentum, d.max_speed};
  for (const RigidBody& b : sim.state().rigid_bodies) {
    row.push_back(b.xg - b.xg0);
    row.push_back(b.yg - b.yg0);
    row.push_back(b.angle);
  }
  const ParticleStore& p = sim.particles();
  for (std::size_t b = 0; b < sim.spec().bodies.size(); ++b) {
    if (sim.spec().bodies[b].kind != Kind::elastic) continue;
    const Range r = sim.body_ranges()[b];
    const auto [xmin, xmax] = std::minmax_element(p.x.begin() + r.begin, p.x.begin() + r.end);
    const auto [ymin, ymax] = std::minmax_element(p.y.begin() + r.begin, p.y.begin() + r.end);
    row.insert(row.end(), {*xmin, *xmax, *ymin, *ymax});
  }
  return row;
}

HistoryWriter::HistoryWriter(const std::filesystem::path& path, const Simulation& sim)
    : path_(path) {
  file_ = std::fopen(staging_path(path).c_str(), "w");
  if (!file_) throw std::runtime_error(fmt::format("cannot write {}", staging_path(path).string()));
  std::string header;
  for (const auto& c : history_columns(sim)) header += (header.empty() ? "" : ",") + c;
  header += '\n';
  bytes_ += std::fwrite(header.data(), 1, header.size(), file_);
}

HistoryWriter::~HistoryWriter() {
  if (file_) std::fclose(file_);
}

void HistoryWriter::write(const Simulation& sim, const Diagnostics& d) {
  std::string line;
  for (double v : history_row(sim, d)) {
    if (!line.empty()) line += ',';
    line += fmt::format("{:.17g}", v);
  }
  line += '\n';
  bytes_ += std::fwrite(line.data(), 1, line.size(), file_);
  std::fflush(file_);  // a crashed run keeps every frame written so far
}

void HistoryWriter::publish() {
  std::fclose(file_);
  file_ = nullptr;
  publish_staged_file(path_);
}

}  // namespace mpsolid
