#include "src/io/frame_writer.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "src/io/atomic_file.hpp"
#include "src/io/hdf5_file.hpp"

namespace mpsolid {

const std::vector<XdmfField>& frame_fields(int dimension) {
  // The frame's datasets but the position (the grid's geometry) and the
  // orientation quaternion (the rotation vector stands for it).
  static const auto of = [](int d) {
    std::vector<XdmfField> out;
    for (const RowLayout& f : frame_row_layout(d)) {
      const std::string name = f.name;
      if (name == "position" || name == "orientation") continue;
      const char* type = f.type == RowType::f64 ? "Float" : f.type == RowType::i32 ? "Int" : "Char";
      out.push_back(
          {name, type, static_cast<int>(element_bytes(f.type)), static_cast<int>(f.columns)});
    }
    return out;
  };
  static const std::vector<XdmfField> plane = of(2), space = of(3);
  return dimension == 3 ? space : plane;
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

// A dataset of `rows` rows of the field's type, reserved for rows written in
// place (h5::Group::reserve).
std::uint64_t reserve_rows(const h5::Group& group, const RowLayout& field, std::size_t rows) {
  switch (field.type) {
    case RowType::f64:
      return group.reserve<double>(field.name, rows, field.columns);
    case RowType::i32:
      return group.reserve<std::int32_t>(field.name, rows, field.columns);
    case RowType::i8:
      return group.reserve<std::int8_t>(field.name, rows, field.columns);
  }
  return 0;
}

// A compressed dataset of a field, its rows written chunk by chunk.
void create_rows(const h5::Group& group, const RowLayout& field, std::size_t rows, int deflate) {
  switch (field.type) {
    case RowType::f64:
      return group.create<double>(field.name, rows, field.columns, deflate);
    case RowType::i32:
      return group.create<std::int32_t>(field.name, rows, field.columns, deflate);
    case RowType::i8:
      return group.create<std::int8_t>(field.name, rows, field.columns, deflate);
  }
}

std::filesystem::path sidecar_path(const std::filesystem::path& path) {
  return path.parent_path() / (path.stem().string() + ".xdmf");
}
}  // namespace

FrameWriter::FrameWriter(const std::filesystem::path& path, const SolverState& state,
                         const CaseSpec& spec, std::uint64_t run_id, std::size_t particles)
    : path_(path),
      file_(std::make_unique<File>()),
      compression_(spec.compression),
      particles_(particles),
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
                         const CaseSpec& spec, std::uint64_t run_id, std::size_t particles,
                         int keep_frames)
    : path_(path),
      file_(std::make_unique<File>()),
      compression_(spec.compression),
      particles_(particles),
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

h5::Group FrameWriter::begin_frame(std::int64_t step, const CaseSpec& spec) {
  h5::Group group = file_->frames.create_group(frame_group(frames_total()));
  group.set_attribute<std::int64_t>("step", step);
  group.set_attribute<double>("time", spec.time_at(step));
  return group;
}

void FrameWriter::end_frame(const h5::Group& group, std::int64_t step, const CaseSpec& spec,
                            const GasFrame& gas) {
  if (!gas.empty()) {
    const int level = compression_;
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
  frames_.push_back({"/frames/" + frame_group(frames_total()), spec.time_at(step)});
}

void FrameWriter::write(const SolverState& state, const CaseSpec& spec, const GasFrame& gas) {
  const ParticleStore& p = state.particles;
  const h5::Group group = begin_frame(state.step, spec);
  if (p.dimension != 3 && !surfaces_built_) {
    std::vector<std::pair<Kind, const Shape*>> bodies;
    for (const BodySpec& b : spec.bodies) bodies.emplace_back(b.kind, &b.shape);
    surfaces_ = frame_surfaces(bodies, state.body_ranges, spec.l0);
    surfaces_built_ = true;
  }
  const SurfaceMarks marks = whole_surface_marks(state, surfaces_);
  for (const RowLayout& field : frame_row_layout(p.dimension))
    std::visit(
        [&](const auto& values) { group.write(field.name, values, field.columns, compression_); },
        frame_rows(field, p, file_->storage_of_id, marks));
  end_frame(group, state.step, spec, gas);
}

void FrameWriter::write_placed(std::int64_t step, const CaseSpec& spec, const GasFrame& gas,
                               const RowPlacer& placer) {
  const h5::Group group = begin_frame(step, spec);
  RowPlacement placement{RowPlacement::Content::frame,
                         std::filesystem::absolute(staging_path(path_)).string(),
                         {},
                         {}};
  const std::vector<RowLayout>& fields = frame_row_layout(dimension_);
  if (compression_ > 0) {
    // HDF5 compresses whole chunks: the ranks' rows come here chunk by chunk.
    placement.content = RowPlacement::Content::compressed_frame;
    placement.offsets = {particles_, h5::kChunkRows};
    for (const RowLayout& field : fields) create_rows(group, field, particles_, compression_);
    placement.chunk_sink = [&](std::uint64_t first, const std::vector<RowValues>& rows) {
      for (std::size_t f = 0; f < fields.size(); ++f)
        std::visit(
            [&](const auto& values) {
              group.write_rows(fields[f].name, first, values, fields[f].columns);
            },
            rows[f]);
    };
  } else {
    for (const RowLayout& field : fields)
      placement.offsets.push_back(reserve_rows(group, field, particles_));
  }
  placer(placement);
  end_frame(group, step, spec, gas);
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
