#include "src/solver/rank_rows.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "src/core/hash.hpp"
#include "src/distributed/placed_rows.hpp"

namespace mpsolid {

std::string encode_placement(const RowPlacement& placement) {
  std::string text =
      fmt::format("{} {}", static_cast<int>(placement.content), placement.offsets.size());
  for (const std::uint64_t offset : placement.offsets) text += fmt::format(" {}", offset);
  return text + "\n" + placement.file;
}

RowPlacement decode_placement(const std::string& text) {
  const std::size_t line = text.find('\n');
  if (line == std::string::npos) throw std::invalid_argument("decode_placement: no file");
  std::istringstream head(text.substr(0, line));
  RowPlacement out;
  int content = 0;
  std::size_t count = 0;
  head >> content >> count;
  out.content = static_cast<RowPlacement::Content>(content);
  out.offsets.resize(count);
  for (std::uint64_t& offset : out.offsets) head >> offset;
  if (!head) throw std::invalid_argument("decode_placement: a short placement");
  out.file = text.substr(line + 1);
  return out;
}

namespace {
// The frame's surface marks of the part's owned particles.
SurfaceMarks rank_surface_marks(const RankPart& part, const RankGroup& world,
                                const std::vector<FrameSurface>& surfaces) {
  const ParticleStore& p = part.local.particles;
  const LocalLayout& layout = part.layout;
  if (p.dimension == 3) return space_surface_marks(part.local, layout.owned);
  const auto owns = [&](std::size_t g) { return layout.owns(g); };
  const auto local_of = [&](std::size_t g) { return layout.find(g); };
  NodePositions nodes = surface_nodes(surfaces, p.x.data(), p.y.data(), local_of, owns);
  // Each rank's nodes (surface, node, x, y) to every rank.
  std::vector<double> mine;
  for (std::size_t s = 0; s < surfaces.size(); ++s) {
    const auto& [first, surface] = surfaces[s];
    for (std::size_t k = 0; k < surface.nodes(); ++k)
      if (owns(first + surface.host[k]))
        mine.insert(mine.end(),
                    {static_cast<double>(s), static_cast<double>(k), nodes[s][k].x, nodes[s][k].y});
  }
  const std::vector<double> all = world.all_gather(mine);
  for (std::size_t at = 0; at + 3 < all.size(); at += 4)
    nodes[static_cast<std::size_t>(all[at])][static_cast<std::size_t>(all[at + 1])] = {all[at + 2],
                                                                                       all[at + 3]};
  return plane_surface_marks(surfaces, nodes, p.size(), [&](std::size_t g) -> std::int64_t {
    return owns(g) ? static_cast<std::int64_t>(layout.local_of_owned(g)) : -1;
  });
}

// A 64-bit hash in two doubles (each half exact).
void append_hash(std::uint64_t h, std::vector<double>& out) {
  out.push_back(static_cast<double>(h >> 32));
  out.push_back(static_cast<double>(h & 0xffffffffull));
}
std::uint64_t read_hash(const std::vector<double>& in, std::size_t at) {
  return (static_cast<std::uint64_t>(in.at(at)) << 32) | static_cast<std::uint64_t>(in.at(at + 1));
}

// A checkpoint's particle arrays: the members' rows written from the store,
// or (`restore`) read into it; returns each array's hash terms summed.
std::vector<std::uint64_t> place_state_arrays(ParticleStore& p, const IdRuns& runs,
                                              const RowPlacement& placement, PlacedFile& file) {
  const bool restore = placement.content == RowPlacement::Content::restore;
  const std::vector<StateArray>& arrays = state_arrays(p.dimension);
  std::vector<std::uint64_t> hashes;
  std::vector<double> values(runs.members.size());
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    std::vector<double>& stored = p.*arrays[a].member;
    if (restore) file.read(placement.offsets.at(a), sizeof(double), runs, values.data());
    std::uint64_t hash = 0;
    for (std::size_t k = 0; k < values.size(); ++k) {
      const std::size_t i = runs.members[k];
      if (restore)
        stored[i] = values[k];
      else
        values[k] = stored[i];
      hash += placed_term(static_cast<std::uint64_t>(p.id[i]), values[k]);
    }
    if (!restore) file.write(placement.offsets.at(a), sizeof(double), runs, values.data());
    hashes.push_back(hash);
  }
  return hashes;
}
}  // namespace

void append_rank_rows(RankPart& part, const RankGroup& world,
                      const std::vector<FrameSurface>& surfaces, const RowPlacement& placement,
                      std::vector<double>& out) {
  ParticleStore& p = part.local.particles;
  const bool frame = placement.content == RowPlacement::Content::frame;
  std::optional<SurfaceMarks> marks;
  if (frame) marks = rank_surface_marks(part, world, surfaces);
  const IdRuns runs = id_runs(p.id, part.layout.owned);
  std::vector<std::uint64_t> hashes;
  int error = 0;
  try {
    PlacedFile file(placement.file, placement.content == RowPlacement::Content::restore
                                        ? PlacedFile::Access::read
                                        : PlacedFile::Access::write);
    if (frame) {
      const std::vector<RowLayout>& fields = frame_row_layout(p.dimension);
      for (std::size_t f = 0; f < fields.size(); ++f)
        std::visit(
            [&](const auto& values) {
              file.write(placement.offsets.at(f), fields[f].row_bytes(), runs, values.data());
            },
            frame_rows(fields[f], p, runs.members, *marks));
    } else {
      hashes = place_state_arrays(p, runs, placement, file);
    }
    file.close();
  } catch (const PlacedRowsError& e) {
    error = e.error_number != 0 ? e.error_number : EIO;
  }
  out.insert(out.end(), {static_cast<double>(error), static_cast<double>(hashes.size())});
  for (const std::uint64_t h : hashes) append_hash(h, out);
}

FrameChunks::FrameChunks(const RankPart& part, const RankGroup& world,
                         const std::vector<FrameSurface>& surfaces, const RowPlacement& placement)
    : particles_(part.local.particles),
      marks_(rank_surface_marks(part, world, surfaces)),
      members_(id_runs(part.local.particles.id, part.layout.owned).members),
      total_(placement.offsets.at(0)),
      per_chunk_(placement.offsets.at(1)),
      chunks_(static_cast<std::size_t>((total_ + per_chunk_ - 1) / per_chunk_)) {}

std::vector<double> FrameChunks::rows(std::size_t c) const {
  // The members whose ids fall in the chunk: a run of members_ (by id).
  const auto id_of = [&](std::size_t i) { return static_cast<std::uint64_t>(particles_.id[i]); };
  const std::uint64_t first = c * per_chunk_, end = std::min(total_, first + per_chunk_);
  const auto from = std::partition_point(members_.begin(), members_.end(),
                                         [&](std::size_t i) { return id_of(i) < first; });
  const auto to =
      std::partition_point(from, members_.end(), [&](std::size_t i) { return id_of(i) < end; });
  const std::vector<std::size_t> chunk(from, to);
  std::vector<double> out;
  for (const RowLayout& field : frame_row_layout(particles_.dimension))
    std::visit([&](const auto& values) { out.insert(out.end(), values.begin(), values.end()); },
               frame_rows(field, particles_, chunk, marks_));
  return out;
}

ChunkRows::ChunkRows(int dimension, std::uint64_t first, std::size_t count)
    : layout_(frame_row_layout(dimension)), first_(first) {
  for (const RowLayout& field : layout_) {
    const std::size_t n = count * field.columns;
    switch (field.type) {
      case RowType::f64:
        values_.emplace_back(std::vector<double>(n));
        break;
      case RowType::i32:
        values_.emplace_back(std::vector<std::int32_t>(n));
        break;
      case RowType::i8:
        values_.emplace_back(std::vector<std::int8_t>(n));
        break;
    }
  }
}

void ChunkRows::add(const std::vector<double>& rows) {
  std::size_t columns = 0;
  for (const RowLayout& field : layout_) columns += field.columns;
  const std::size_t count = rows.size() / columns;
  if (count * columns != rows.size() || layout_.front().columns != 1)
    throw std::runtime_error("a rank's rows of a frame chunk cut short");
  // The first dataset is the id: where each row goes.
  std::vector<std::size_t> at(count);
  for (std::size_t k = 0; k < count; ++k)
    at[k] = static_cast<std::size_t>(static_cast<std::uint64_t>(rows[k]) - first_);
  std::size_t read = 0;
  for (std::size_t f = 0; f < layout_.size(); ++f) {
    const std::size_t width = layout_[f].columns;
    std::visit(
        [&](auto& values) {
          using T = typename std::decay_t<decltype(values)>::value_type;
          for (std::size_t k = 0; k < count; ++k)
            for (std::size_t j = 0; j < width; ++j)
              values.at(at[k] * width + j) = static_cast<T>(rows[read + k * width + j]);
        },
        values_[f]);
    read += count * width;
  }
}

std::string read_rank_rows(const std::vector<double>& in, std::size_t& at, int rank,
                           const RowPlacement& placement, PlacedRows& total) {
  const int error = static_cast<int>(in.at(at));
  const auto count = static_cast<std::size_t>(in.at(at + 1));
  at += 2;
  if (total.array_hashes.empty()) total.array_hashes.assign(count, 0);
  for (std::size_t a = 0; a < count; ++a, at += 2) total.array_hashes.at(a) += read_hash(in, at);
  if (error == 0) return "";
  return fmt::format("{}: rank {} could not {} its particles' rows: {}", placement.file, rank,
                     placement.content == RowPlacement::Content::restore ? "read" : "write",
                     std::strerror(error));
}

}  // namespace mpsolid
