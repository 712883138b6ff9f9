// Checkpoints: a write-read round trip keeps every bit; a simulation resumed
// from a checkpoint file (set up afresh from the stored case, then the state
// overwritten) goes on to the same bits as one that never stopped, at another
// thread count too, before and after a load switches on; a checkpoint that
// does not fit is refused.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "src/core/hash.hpp"
#include "src/core/parallel.hpp"
#include "src/distributed/placed_rows.hpp"
#include "src/io/checkpoint.hpp"
#include "src/io/hdf5_file.hpp"
#include "src/solver/case_loader.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

class TempDir {
 public:
  TempDir() {
    path_ =
        std::filesystem::temp_directory_path() /
        ("mpsolid_checkpoint_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
         "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Every evolving quantity of two simulations is equal bit for bit.
void expect_same_state(Simulation& a, Simulation& b) {
  ASSERT_EQ(a.step(), b.step());
  EXPECT_TRUE(testing::same_bits(a.particles(), b.particles()));
  ASSERT_EQ(a.state().rigid_bodies.size(), b.state().rigid_bodies.size());
  for (std::size_t k = 0; k < a.state().rigid_bodies.size(); ++k) {
    const RigidBody &u = a.state().rigid_bodies[k], &v = b.state().rigid_bodies[k];
    EXPECT_TRUE(testing::same_bits(pose_values(u), pose_values(v))) << u.name;
  }
  ASSERT_EQ(a.state().loads.size(), b.state().loads.size());
  for (std::size_t k = 0; k < a.state().loads.size(); ++k) {
    EXPECT_EQ(a.state().loads[k].active, b.state().loads[k].active);
    EXPECT_TRUE(same_bits(a.state().loads[k].cx_on, b.state().loads[k].cx_on));
    EXPECT_TRUE(same_bits(a.state().loads[k].cy_on, b.state().loads[k].cy_on));
    const StepLoad &u = a.state().loads[k], &v = b.state().loads[k];
    for (auto [p, q] : {std::pair{u.factor, v.factor},
                        {u.cx_last, v.cx_last},
                        {u.cy_last, v.cy_last},
                        {u.work, v.work}})
      EXPECT_TRUE(same_bits(p, q)) << u.name;
    EXPECT_EQ(u.surface.x, v.surface.x) << u.name;
    EXPECT_EQ(u.surface.y, v.surface.y) << u.name;
    EXPECT_EQ(u.surface.target_fx, v.surface.target_fx) << u.name;
  }
  for (std::size_t k = 0; k < a.state().rigid_bodies.size(); ++k)
    EXPECT_TRUE(same_bits(a.state().rigid_bodies[k].work, b.state().rigid_bodies[k].work));
  const Diagnostics da = a.diagnostics(), db = b.diagnostics();
  EXPECT_TRUE(same_bits(da.kinetic_energy, db.kinetic_energy));
  EXPECT_TRUE(same_bits(da.strain_energy, db.strain_energy));
  EXPECT_TRUE(same_bits(da.external_work, db.external_work));
  EXPECT_TRUE(same_bits(da.angular_momentum, db.angular_momentum));
}

Checkpoint full_checkpoint(Simulation& sim) {
  Checkpoint c = capture_state(sim.state());
  c.case_toml = sim.spec().resolved_toml;
  c.bond_hash = sim.state().bonds.hash();
  c.run_id = 42;
  c.frames = 3;
  c.history_bytes = 1234;
  c.written_by = "test";
  c.segments = {"{\"a\": 1}", "{\"b\": 2}"};
  return c;
}

// Runs `first` steps, checkpoints to a file, resumes a fresh simulation set
// up from the stored case at `threads`, and runs both to `first + second`.
void expect_resume_is_seamless(const std::vector<std::string>& overrides, std::int64_t first,
                               std::int64_t second, int threads,
                               const std::string& case_file = "cases/shock_rod.toml") {
  TempDir dir;
  set_thread_count(1);
  Simulation uninterrupted(load_case(testing::source_path(case_file), overrides));
  uninterrupted.advance(first);
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  write_checkpoint(path, full_checkpoint(uninterrupted));
  uninterrupted.advance(second);

  set_thread_count(threads);
  const Checkpoint c = read_checkpoint(path);
  Simulation resumed(load_case_text(c.case_toml, path.string()));
  restore_state(resumed.state_to_change(), c, path.string());
  EXPECT_EQ(resumed.step(), first);
  resumed.advance(second);
  set_thread_count(1);
  expect_same_state(uninterrupted, resumed);
  set_thread_count(available_cores());
}

TEST(Checkpoint, RoundTripKeepsEveryBit) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  sim.advance(50);
  const Checkpoint c = full_checkpoint(sim);
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  const std::uintmax_t bytes = write_checkpoint(path, c);
  EXPECT_EQ(bytes, std::filesystem::file_size(path));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "checkpoint.h5.tmp"));
  const Checkpoint r = read_checkpoint(path);
  EXPECT_EQ(r.step, 50);
  EXPECT_EQ(r.case_toml, c.case_toml);
  EXPECT_EQ(r.bond_hash, c.bond_hash);
  EXPECT_EQ(r.run_id, c.run_id);
  EXPECT_EQ(r.frames, c.frames);
  EXPECT_EQ(r.history_bytes, c.history_bytes);
  EXPECT_EQ(r.written_by, c.written_by);
  EXPECT_EQ(r.segments, c.segments);
  ASSERT_EQ(r.particle_arrays.size(), state_arrays(2).size());
  for (std::size_t a = 0; a < c.particle_arrays.size(); ++a) {
    EXPECT_EQ(r.particle_arrays[a].first, c.particle_arrays[a].first);
    const auto &u = r.particle_arrays[a].second, &v = c.particle_arrays[a].second;
    ASSERT_EQ(u.size(), v.size());
    EXPECT_EQ(std::memcmp(u.data(), v.data(), u.size() * sizeof(double)), 0);
  }
  ASSERT_EQ(r.rigid_bodies.size(), 1u);
  EXPECT_EQ(r.rigid_bodies[0].name, "plate");
  EXPECT_TRUE(testing::same_bits(r.rigid_bodies[0].pose, c.rigid_bodies[0].pose));
  ASSERT_EQ(r.loads.size(), 1u);
  EXPECT_TRUE(r.loads[0].active);
  EXPECT_TRUE(same_bits(r.loads[0].cx_on, c.loads[0].cx_on));
}

// Arrays are stored in id order: storage order is an implementation detail.
TEST(Checkpoint, ParticleArraysAreInIdOrder) {
  Simulation sim(testing::rod_case());
  sim.advance(10);
  const Checkpoint c = capture_state(sim.state());
  const ParticleStore& p = sim.particles();
  ASSERT_EQ(c.particle_arrays[0].first, "x");
  for (std::size_t i = 0; i < p.size(); ++i)
    EXPECT_TRUE(same_bits(c.particle_arrays[0].second[static_cast<std::size_t>(p.id[i])], p.x[i]));
}

TEST(Checkpoint, ResumedRunIsBitIdentical) {
  expect_resume_is_seamless({}, 400, 400, 1);
}

TEST(Checkpoint, ResumedRunIsBitIdenticalAtTwoThreads) {
  expect_resume_is_seamless({"l0=0.001"}, 40, 40, 2);
}

// The load's switch-on (and its centroid record) is part of the state: a
// checkpoint before the switch-on, and one after it.
TEST(Checkpoint, ResumeAcrossALoadSwitchOn) {
  expect_resume_is_seamless({"loads.shock.start=1.5e-6"}, 100, 100, 2);
  expect_resume_is_seamless({"loads.shock.start=0.5e-6"}, 100, 100, 1);
}

// A varying load's factor, last centroid and work are part of the state: a
// checkpoint in the middle of a ramp and of a blast wave.
TEST(Checkpoint, ResumeInTheMiddleOfARampAndABlastWave) {
  expect_resume_is_seamless({"loads.shock.history=\"ramp\"", "loads.shock.rise_time=2e-6"}, 100,
                            100, 2);
  expect_resume_is_seamless({"loads.shock.history=\"friedlander\"", "loads.shock.duration=1e-6",
                             "loads.shock.decay=1.5", "loads.shock.start=0.3e-6"},
                            100, 100, 1);
}

// A pressure's running step (its nodes' positions at the step's start) is
// part of the state: a checkpoint in the middle of a blast wave on a disk,
// and of a ramped pressure on the rod's plate.
TEST(Checkpoint, ResumeInTheMiddleOfAPressure) {
  expect_resume_is_seamless({"l0=0.001"}, 30, 30, 2, "cases/disk_blast.toml");
  expect_resume_is_seamless({"loads.shock.history=\"ramp\"", "loads.shock.rise_time=2e-6"}, 100,
                            100, 2, "cases/shock_rod_pressure.toml");
}

// A driven body's work is part of the state: a checkpoint in the middle of
// the grips' ramp.
TEST(Checkpoint, ResumeInTheMiddleOfAPrescribedMotion) {
  expect_resume_is_seamless({"l0=0.001"}, 200, 200, 2, "cases/holed_plate_grips.toml");
}

TEST(Checkpoint, RefusesAnotherBondTable) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  Checkpoint c = full_checkpoint(sim);
  c.bond_hash ^= 1;  // as if another build had made the table
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  write_checkpoint(path, c);
  Simulation fresh(testing::rod_case());
  try {
    restore_state(fresh.state_to_change(), read_checkpoint(path), path.string());
    FAIL() << "restored a checkpoint with another bond table";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bond table differs"), std::string::npos) << e.what();
  }
}

// The bond hash covers topology and reference geometry, not material
// constants: those are the case's, which the checkpoint stores whole.
TEST(Checkpoint, BondHashIsTopologyAndGeometryOnly) {
  const std::uint64_t base = Simulation(testing::rod_case()).state().bonds.hash();
  EXPECT_EQ(Simulation(testing::rod_case({"materials.rubber.E=5.0e6"})).state().bonds.hash(), base);
  EXPECT_EQ(Simulation(testing::rod_case({"model=finite_strain"})).state().bonds.hash(), base);
  EXPECT_NE(Simulation(testing::rod_case({"l0=0.0025"})).state().bonds.hash(), base);
  EXPECT_NE(Simulation(testing::rod_case({"bodies.rod.x=[0.0, 0.098]"})).state().bonds.hash(),
            base);
}

TEST(Checkpoint, RefusesAnOlderFormatNamingItsWriter) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  write_checkpoint(path, full_checkpoint(sim));
  h5::File::open(path, true).set_attribute<std::int64_t>("format_version", 2);
  try {
    read_checkpoint(path);
    FAIL() << "read a checkpoint of an older format";
  } catch (const InputError& e) {
    const std::string message = e.what();
    for (const char* needle : {"format version 2", "reads versions 3 to 4", "older format",
                               "run the case afresh", "mpsolid"})
      EXPECT_NE(message.find(needle), std::string::npos) << needle << " in: " << message;
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  }
}

// A placer that writes every particle's arrays in place from the whole
// state, as the ranks do with theirs (src/solver/rank_rows.cpp), here in
// two parts cut at `cut`.
RowPlacer whole_state_placer(const SolverState& s, std::size_t cut) {
  return [&s, cut](const RowPlacement& placement) {
    EXPECT_EQ(placement.content, RowPlacement::Content::checkpoint);
    const ParticleStore& p = s.particles;
    const std::vector<StateArray>& arrays = state_arrays(p.dimension);
    PlacedRows out;
    out.array_hashes.assign(arrays.size(), 0);
    for (const Range part : {Range{0, cut}, Range{cut, p.size()}}) {
      const IdRuns runs = id_runs(p.id, part);
      PlacedFile file(placement.file);
      for (std::size_t a = 0; a < arrays.size(); ++a) {
        std::vector<double> values;
        for (const std::size_t i : runs.members) {
          values.push_back((p.*arrays[a].member)[i]);
          out.array_hashes[a] += placed_term(static_cast<std::uint64_t>(p.id[i]), values.back());
        }
        file.write(placement.offsets.at(a), sizeof(double), runs, values.data());
      }
      file.close();
    }
    return out;
  };
}

TEST(Checkpoint, ParticleArraysWrittenInPlaceReadAsWrittenWhole) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  sim.advance(7);
  const Checkpoint whole = full_checkpoint(sim);
  write_checkpoint(dir.path() / "whole.h5", whole);
  Checkpoint named = whole;
  named.particle_arrays = capture_state(sim.state(), false).particle_arrays;
  for (const auto& [name, values] : named.particle_arrays) EXPECT_TRUE(values.empty()) << name;
  write_checkpoint(dir.path() / "placed.h5", named,
                   whole_state_placer(sim.state(), sim.particle_count() / 3));
  const Checkpoint a = read_checkpoint(dir.path() / "whole.h5");
  const Checkpoint b = read_checkpoint(dir.path() / "placed.h5");  // its hash checked
  ASSERT_EQ(a.particle_arrays.size(), b.particle_arrays.size());
  for (std::size_t k = 0; k < a.particle_arrays.size(); ++k) {
    EXPECT_EQ(a.particle_arrays[k].first, b.particle_arrays[k].first);
    EXPECT_EQ(0, std::memcmp(a.particle_arrays[k].second.data(), b.particle_arrays[k].second.data(),
                             a.particle_arrays[k].second.size() * sizeof(double)))
        << a.particle_arrays[k].first;
  }
  EXPECT_EQ(
      h5::File::open(dir.path() / "whole.h5", false).attribute<std::uint64_t>("content_hash"),
      h5::File::open(dir.path() / "placed.h5", false).attribute<std::uint64_t>("content_hash"));
}

// A checkpoint of format 3 (each particle array's bytes in its content hash;
// tests/regression/data/README.md) still reads, its hash checked, and resumes
// to the bits of a run that never stopped; a changed value in it is found.
TEST(Checkpoint, AFormat3CheckpointResumesToTheSameBits) {
  const std::filesystem::path path =
      testing::source_path("tests/regression/data/shock_rod_checkpoint_format3.h5");
  set_thread_count(1);
  const Checkpoint c = read_checkpoint(path);
  EXPECT_EQ(h5::File::open(path, false).attribute<std::int64_t>("format_version"), 3);
  EXPECT_EQ(c.step, 1000);
  Simulation resumed(load_case_text(c.case_toml, path.string()));
  restore_state(resumed.state_to_change(), c, path.string());
  resumed.advance(500);
  Simulation straight(load_case_text(c.case_toml, path.string()));
  straight.advance(1500);
  expect_same_state(straight, resumed);
  set_thread_count(available_cores());

  TempDir dir;
  const std::filesystem::path changed = dir.path() / "checkpoint.h5";
  std::filesystem::copy_file(path, changed);
  {
    const h5::File file = h5::File::open(changed, true);
    const h5::Group particles = file.open_group("particles");
    std::vector<double> x = particles.read<double>("x", c.particle_arrays[0].second.size());
    x[17] = std::nextafter(x[17], 1.0);
    particles.remove("x");
    particles.write("x", x);
  }
  EXPECT_THROW(read_checkpoint(changed), InputError);
}

// Read with ParticleRows::placed, a checkpoint (written whole or in place)
// names where each particle array lies: every row read in place there is
// the row read whole, and their hashes check the stored content hash (a
// changed one is refused). A format-3 file cannot be read in place.
TEST(Checkpoint, ReadInPlaceEveryRowIsWhereItsOffsetSaysAndItsHashChecks) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  sim.advance(7);
  const Checkpoint whole = full_checkpoint(sim);
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  write_checkpoint(path, whole);
  const Checkpoint placed = read_checkpoint(path, ParticleRows::placed);
  ASSERT_EQ(placed.particle_offsets.size(), whole.particle_arrays.size());
  ASSERT_EQ(placed.particle_arrays.size(), whole.particle_arrays.size());
  EXPECT_EQ(placed.step, whole.step);
  EXPECT_EQ(placed.rigid_bodies.size(), whole.rigid_bodies.size());
  const auto n = static_cast<std::size_t>(placed.particle_count);
  std::vector<std::int32_t> ids(n);
  for (std::size_t k = 0; k < n; ++k) ids[k] = static_cast<std::int32_t>(n - 1 - k);
  std::vector<std::uint64_t> hashes;
  PlacedFile file(path.string(), PlacedFile::Access::read);
  for (std::size_t a = 0; a < placed.particle_arrays.size(); ++a) {
    EXPECT_EQ(placed.particle_arrays[a].first, whole.particle_arrays[a].first);
    EXPECT_TRUE(placed.particle_arrays[a].second.empty());
    // Two "ranks", the second holding the first ids, in reverse storage.
    std::vector<double> rows(n);
    std::uint64_t hash = 0;
    for (const Range part : {Range{0, n / 3}, Range{n / 3, n}}) {
      const IdRuns runs = id_runs(ids, part);
      std::vector<double> mine(runs.members.size());
      file.read(placed.particle_offsets[a], sizeof(double), runs, mine.data());
      for (std::size_t k = 0; k < mine.size(); ++k) {
        const auto id = static_cast<std::size_t>(ids[runs.members[k]]);
        rows[id] = mine[k];
        hash += placed_term(id, mine[k]);
      }
    }
    EXPECT_EQ(0, std::memcmp(rows.data(), whole.particle_arrays[a].second.data(), n * 8))
        << placed.particle_arrays[a].first;
    hashes.push_back(hash);
  }
  EXPECT_NO_THROW(check_placed_content(placed, hashes, path.string()));
  hashes.back() += 1;
  EXPECT_THROW(check_placed_content(placed, hashes, path.string()), InputError);

  const Checkpoint old =
      read_checkpoint(testing::source_path("tests/regression/data/shock_rod_checkpoint_format3.h5"),
                      ParticleRows::placed);
  EXPECT_TRUE(old.particle_offsets.empty());
  EXPECT_TRUE(old.particle_arrays.empty());
}

// Without the particles (rank 0 keeping no copy), a restore checks the fit
// against the run's counts and bond hash, then sets the bodies and step.
TEST(Checkpoint, ARestoreWithoutParticlesChecksTheRunsCountsAndSetsTheBodies) {
  Simulation sim(testing::rod_case());
  sim.advance(9);
  const Checkpoint c = full_checkpoint(sim);
  const std::size_t n = sim.particle_count();
  const std::uint64_t hash = sim.bond_hash();
  Simulation fresh(testing::rod_case());
  SolverState head = fresh.state();
  head.particles = ParticleStore{};
  head.particles.dimension = 2;
  Checkpoint placed = c;
  placed.particle_offsets.assign(placed.particle_arrays.size(), 0);
  for (auto& [name, values] : placed.particle_arrays) values.clear();
  EXPECT_THROW(restore_state_without_particles(head, n + 1, hash, placed, "test"), InputError);
  EXPECT_THROW(restore_state_without_particles(head, n, hash ^ 1, placed, "test"), InputError);
  restore_state_without_particles(head, n, hash, placed, "test");
  EXPECT_EQ(head.step, 9);
  ASSERT_EQ(head.rigid_bodies.size(), sim.state().rigid_bodies.size());
  for (std::size_t b = 0; b < head.rigid_bodies.size(); ++b)
    EXPECT_EQ(pose_values(head.rigid_bodies[b]), pose_values(sim.state().rigid_bodies[b]));
}

TEST(Checkpoint, RefusesOtherStateArraysOrParticleCount) {
  Simulation sim(testing::rod_case());
  Checkpoint c = full_checkpoint(sim);
  Checkpoint missing = c;
  missing.particle_arrays.pop_back();
  EXPECT_THROW(restore_state(sim.state_to_change(), missing, "test"), InputError);
  Checkpoint shorter = c;
  for (auto& [name, values] : shorter.particle_arrays) values.pop_back();
  EXPECT_THROW(restore_state(sim.state_to_change(), shorter, "test"), InputError);
  Checkpoint renamed = c;
  renamed.rigid_bodies[0].name = "lid";
  EXPECT_THROW(restore_state(sim.state_to_change(), renamed, "test"), InputError);
}

TEST(Checkpoint, RefusesADamagedFile) {
  TempDir dir;
  Simulation sim(testing::rod_case());
  sim.advance(5);
  const std::filesystem::path path = dir.path() / "checkpoint.h5";
  write_checkpoint(path, full_checkpoint(sim));
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  // The particle arrays are the bulk of the file: a flipped bit there is
  // invisible to HDF5 and must be found by the content hash.
  const double needle = sim.particles().x[sim.particles().storage_of_id()[777]];
  const std::size_t at = bytes.find(std::string(reinterpret_cast<const char*>(&needle), 8));
  ASSERT_NE(at, std::string::npos);
  bytes[at + 3] = static_cast<char>(bytes[at + 3] ^ 0x04);
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  try {
    read_checkpoint(path);
    FAIL() << "read a damaged checkpoint";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("damaged"), std::string::npos) << e.what();
  }
  std::filesystem::resize_file(path, bytes.size() / 3);
  EXPECT_THROW(read_checkpoint(path), InputError);
  EXPECT_THROW(read_checkpoint(dir.path() / "none.h5"), InputError);
}

}  // namespace
}  // namespace mpsolid
