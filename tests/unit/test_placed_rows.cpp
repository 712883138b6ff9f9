// Rows written in place (src/distributed/placed_rows.hpp) into datasets an
// HDF5 file reserved for them (h5::Group::reserve): ranks writing their
// own rows of scattered ids give the file the HDF5 library reads back
// exactly, and read their own rows of datasets the library wrote
// (h5::Group::placed_offset); a compressed frame's rows sent chunk by chunk
// assemble into the whole frame's; the arrays' hash adds over any split; a placement travels as
// text; failures name the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "src/core/hash.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/placed_rows.hpp"
#include "src/distributed/thread_ranks.hpp"
#include "src/io/hdf5_file.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/distributed_step.hpp"
#include "src/solver/rank_rows.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

std::filesystem::path temp_file(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("mpsolid_test_placed_rows_" + name);
}

// Ids 0..n-1 shuffled: storage order is not id order.
std::vector<std::int32_t> shuffled_ids(std::size_t n, unsigned seed) {
  std::vector<std::int32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::mt19937 random(seed);
  // Keep some runs: shuffle blocks of 7, then within every third block.
  for (std::size_t b = 0; b + 7 <= n; b += 21)
    std::shuffle(ids.begin() + b, ids.begin() + b + 7, random);
  std::reverse(ids.begin() + static_cast<long>(n / 3), ids.begin() + static_cast<long>(n / 2));
  return ids;
}

TEST(IdRuns, OrderByIdAndRunsOfConsecutiveIds) {
  const std::vector<std::int32_t> ids = {7, 3, 4, 0, 5, 9, 8, 1};
  const IdRuns r = id_runs(ids, {1, 7});  // ids 3 4 0 5 9 8
  const std::vector<std::size_t> members = {3, 1, 2, 4, 6, 5};
  EXPECT_EQ(r.members, members);
  ASSERT_EQ(r.runs.size(), 3u);  // 0 | 3 4 5 | 8 9
  EXPECT_EQ(r.runs[0].first_id, 0u);
  EXPECT_EQ(r.runs[0].count, 1u);
  EXPECT_EQ(r.runs[1].first_id, 3u);
  EXPECT_EQ(r.runs[1].count, 3u);
  EXPECT_EQ(r.runs[2].first_id, 8u);
  EXPECT_EQ(r.runs[2].count, 2u);
  EXPECT_TRUE(id_runs(ids, {4, 4}).runs.empty());
}

TEST(PlacedRows, RanksWritingTheirOwnRowsGiveTheFileTheLibraryReadsBack) {
  const std::size_t n = 10'007;
  const std::vector<std::int32_t> ids = shuffled_ids(n, 5);
  // Per particle (by storage index): two doubles and a byte.
  std::vector<double> xy(2 * n);
  std::vector<std::int8_t> flag(n);
  for (std::size_t i = 0; i < n; ++i) {
    xy[2 * i] = 0.5 + static_cast<double>(i);
    xy[2 * i + 1] = -1.0 / (1.0 + static_cast<double>(i));
    flag[i] = static_cast<std::int8_t>(i % 3);
  }
  const std::filesystem::path path = temp_file("frame.h5");
  std::uint64_t at_xy = 0, at_flag = 0;
  {
    h5::File file = h5::File::create(path);
    const h5::Group group = file.create_group("frame");
    group.write<double>("before", {1.0, 2.0, 3.0});
    at_xy = group.reserve<double>("position", n, 2);
    at_flag = group.reserve<std::int8_t>("surface", n);
    group.write<double>("after", {4.0, 5.0});
    EXPECT_EQ(group.reserve<double>("empty", 0), 0u);
    file.close();
  }
  // Three ranks cut anywhere, each writing its rows in id order.
  const std::vector<std::size_t> cuts = {0, 3001, 7777, n};
  double bytes = 0;
  for (std::size_t r = 0; r + 1 < cuts.size(); ++r) {
    const IdRuns runs = id_runs(ids, {cuts[r], cuts[r + 1]});
    std::vector<double> rows_xy;
    std::vector<std::int8_t> rows_flag;
    for (const std::size_t i : runs.members) {
      rows_xy.insert(rows_xy.end(), {xy[2 * i], xy[2 * i + 1]});
      rows_flag.push_back(flag[i]);
    }
    PlacedFile file(path.string());
    file.write(at_xy, 16, runs, rows_xy.data());
    file.write(at_flag, 1, runs, rows_flag.data());
    file.close();
    bytes += file.bytes();
  }
  EXPECT_EQ(bytes, 17.0 * static_cast<double>(n));
  const h5::File file = h5::File::open(path, false);
  const h5::Group group = file.open_group("frame");
  const std::vector<double> read_xy = group.read<double>("position", n, 2);
  const std::vector<std::int8_t> read_flag = group.read<std::int8_t>("surface", n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto id = static_cast<std::size_t>(ids[i]);
    ASSERT_EQ(read_xy[2 * id], xy[2 * i]) << i;
    ASSERT_EQ(read_xy[2 * id + 1], xy[2 * i + 1]) << i;
    ASSERT_EQ(read_flag[id], flag[i]) << i;
  }
  EXPECT_EQ(group.read<double>("before", 3), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(group.read<double>("after", 2), (std::vector<double>{4.0, 5.0}));
  std::filesystem::remove(path);
}

// The other way: the library writes whole datasets, and ranks cut anywhere
// read their own rows of scattered ids in place, each where the library
// says the dataset lies; datasets stored otherwise are not offered.
TEST(PlacedRows, RanksReadTheirOwnRowsOfWhatTheLibraryWrote) {
  const std::size_t n = 10'007;
  const std::vector<std::int32_t> ids = shuffled_ids(n, 9);
  std::vector<double> by_id(n);
  for (std::size_t k = 0; k < n; ++k) by_id[k] = std::sqrt(2.0 + static_cast<double>(k));
  const std::filesystem::path path = temp_file("restore.h5");
  {
    h5::File file = h5::File::create(path);
    file.write<double>("x", by_id);
    file.write<double>("packed", by_id, 1, 4);
    file.write<std::int64_t>("integers", std::vector<std::int64_t>(n, 1));
    file.close();
  }
  std::uint64_t at = 0;
  {
    const h5::File file = h5::File::open(path, false);
    const std::optional<std::uint64_t> x = file.placed_offset<double>("x", n);
    ASSERT_TRUE(x.has_value());
    at = *x;
    EXPECT_FALSE(file.placed_offset<double>("x", n + 1).has_value());  // another shape
    EXPECT_FALSE(file.placed_offset<double>("x", n / 7, 7).has_value());
    EXPECT_FALSE(file.placed_offset<double>("packed", n).has_value());    // compressed
    EXPECT_FALSE(file.placed_offset<double>("integers", n).has_value());  // another type
  }
  const std::vector<std::size_t> cuts = {0, 2500, 2501, 9000, n};
  std::vector<double> read(n, -1.0);  // by storage index
  double bytes = 0;
  for (std::size_t r = 0; r + 1 < cuts.size(); ++r) {
    const IdRuns runs = id_runs(ids, {cuts[r], cuts[r + 1]});
    std::vector<double> rows(runs.members.size());
    PlacedFile file(path.string(), PlacedFile::Access::read);
    file.read(at, sizeof(double), runs, rows.data());
    file.close();
    bytes += file.bytes();
    for (std::size_t k = 0; k < rows.size(); ++k) read[runs.members[k]] = rows[k];
  }
  EXPECT_EQ(bytes, 8.0 * static_cast<double>(n));
  for (std::size_t i = 0; i < n; ++i)
    ASSERT_EQ(read[i], by_id[static_cast<std::size_t>(ids[i])]) << i;
  // A file cut short inside the rows: the read fails, naming the file.
  std::filesystem::resize_file(path, at + 8 * (n / 2));
  PlacedFile file(path.string(), PlacedFile::Access::read);
  std::vector<double> rows(n);
  try {
    file.read(at, sizeof(double), id_runs(ids, {0, n}), rows.data());
    FAIL() << "read past the end of the file";
  } catch (const PlacedRowsError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("read"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(PlacedRows, AFileThatCannotBeOpenedIsNamed) {
  const std::string missing = temp_file("missing/nowhere.h5").string();
  try {
    PlacedFile file(missing);
    FAIL() << "opened a missing file";
  } catch (const PlacedRowsError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    EXPECT_NE(e.error_number, 0);
  }
}

// A compressed frame's rows: each rank's rows of each chunk of ids (a small
// chunk here, so that chunks span ranks), assembled on "rank 0" in any order
// of the ranks, are the whole state's frame rows in id order, bit for bit,
// in the plane (surface marks from the gathered nodes) and in space.
void expect_chunks_give_the_whole_frame(const CaseSpec& spec) {
  SCOPED_TRACE(spec.name);
  set_thread_count(1);
  Simulation sim(spec);
  const SolverState& global = sim.state();
  const ParticleStore& p = global.particles;
  const std::size_t n = p.size();
  std::vector<FrameSurface> surfaces;
  if (p.dimension != 3) {
    std::vector<std::pair<Kind, const Shape*>> bodies;
    for (const BodySpec& b : spec.bodies) bodies.emplace_back(b.kind, &b.shape);
    surfaces = frame_surfaces(bodies, global.body_ranges, spec.l0);
  }
  const SurfaceMarks marks = whole_surface_marks(global, surfaces);
  const std::vector<RowLayout>& layout = frame_row_layout(p.dimension);
  const std::vector<std::size_t> by_id = p.storage_of_id();
  const std::uint64_t per_chunk = 97;
  const RowPlacement placement{RowPlacement::Content::compressed_frame, "", {n, per_chunk}, {}};
  for (const int ranks : {2, 3}) {
    set_thread_count(ranks);
    ThreadMailboxes boxes(ranks);
    // rows[r][c]: rank r's rows of chunk c.
    std::vector<std::vector<std::vector<double>>> rows(static_cast<std::size_t>(ranks));
    run_in_team([&] {
      const auto me = static_cast<int>(team_rank());
      serial_section([&] {
        ThreadRanks world(boxes, me);
        const RankPart part = make_rank_part(spec, global, world);
        const FrameChunks chunks(part, world, surfaces, placement);
        for (std::size_t c = 0; c < chunks.chunks(); ++c)
          rows[static_cast<std::size_t>(me)].push_back(chunks.rows(c));
      });
    });
    set_thread_count(1);
    const std::size_t chunk_count = (n + per_chunk - 1) / per_chunk;
    for (std::size_t c = 0; c < chunk_count; ++c) {
      const std::size_t first = c * per_chunk, count = std::min<std::size_t>(per_chunk, n - first);
      ChunkRows chunk(p.dimension, first, count);
      for (int r = ranks - 1; r >= 0; --r) chunk.add(rows[static_cast<std::size_t>(r)].at(c));
      const std::vector<std::size_t> members(by_id.begin() + static_cast<long>(first),
                                             by_id.begin() + static_cast<long>(first + count));
      for (std::size_t f = 0; f < layout.size(); ++f)
        EXPECT_EQ(chunk.values()[f], frame_rows(layout[f], p, members, marks))
            << layout[f].name << ", chunk " << c << ", " << ranks << " ranks";
    }
  }
  set_thread_count(available_cores());
}

TEST(FrameChunks, RanksRowsChunkByChunkAreTheWholeFramesRows) {
  expect_chunks_give_the_whole_frame(testing::rod_case({"l0=0.002"}));
  expect_chunks_give_the_whole_frame(
      load_case(testing::source_path("cases/spinning_cube.toml"), {}));
}

TEST(PlacedArrayHash, RanksTermsAddToTheWholeArraysHash) {
  std::vector<double> values(5000);
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = std::sin(static_cast<double>(k)) * 1e3;
  const std::uint64_t whole = placed_array_hash(values);
  // Any split, summed in any order.
  for (const std::size_t cut :
       {std::size_t{0}, std::size_t{1}, std::size_t{2500}, std::size_t{4999}}) {
    std::uint64_t a = 0, b = 0;
    for (std::size_t k = 0; k < cut; ++k) a += placed_term(k, values[k]);
    for (std::size_t k = cut; k < values.size(); ++k) b += placed_term(k, values[k]);
    EXPECT_EQ(b + a, whole) << cut;
  }
  // A moved value, a flipped bit, a lost sign: another hash.
  std::vector<double> swapped = values;
  std::swap(swapped[10], swapped[11]);
  EXPECT_NE(placed_array_hash(swapped), whole);
  std::vector<double> flipped = values;
  flipped[4321] = std::nextafter(flipped[4321], 1e9);
  EXPECT_NE(placed_array_hash(flipped), whole);
  std::vector<double> zero = values;
  zero[0] = -0.0;  // values[0] is +0.0
  EXPECT_NE(placed_array_hash(zero), whole);
}

TEST(RowPlacement, TravelsAsText) {
  const RowPlacement p{RowPlacement::Content::checkpoint,
                       "/tmp/a folder/with spaces/checkpoint.h5.tmp",
                       {2048, 18446744073709551000ull, 0},
                       {}};
  const RowPlacement q = decode_placement(encode_placement(p));
  EXPECT_EQ(q.content, p.content);
  EXPECT_EQ(q.file, p.file);
  EXPECT_EQ(q.offsets, p.offsets);
  EXPECT_THROW(decode_placement("0 3 1 2"), std::invalid_argument);
  EXPECT_THROW(decode_placement("0 3 1 2\nfile"), std::invalid_argument);
}

}  // namespace
}  // namespace mpsolid
