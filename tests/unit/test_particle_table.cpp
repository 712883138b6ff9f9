// The particle table (src/core/particle_store.hpp) reaches everything
// derived from it: resize gives every array its initial value; every state
// array goes through a snapshot and a checkpoint file and back, and nothing
// else does; every array goes through a rank's part message. An array
// added to the table is covered here by its line alone.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <set>
#include <string>

#include "src/core/state_snapshot.hpp"
#include "src/distributed/part_message.hpp"
#include "src/io/checkpoint.hpp"
#include "src/solver/distributed_step.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// A value of row `row` at particle i that no other row and no set-up gives.
double pattern(std::size_t row, std::size_t i) {
  return 1000.0 * static_cast<double>(row + 1) + static_cast<double>(i) + 0.125;
}

// Writes the pattern into every double array of `p` whose role is `role`.
void fill(ParticleStore& p, ArrayRole role) {
  std::size_t row = 0;
  for_each_particle_array(p, [&](const auto& info, auto& v) {
    if constexpr (std::is_same_v<typename std::decay_t<decltype(v)>::value_type, double>)
      if (info.role == role)
        for (std::size_t i = 0; i < v.size(); ++i) v[i] = pattern(row, i);
    ++row;
  });
}

std::set<std::string> state_names(int dimension = 2) {
  std::set<std::string> names;
  for_each_particle_member([&](const auto& info, auto) {
    if (info.role == ArrayRole::state && info.present_in(dimension)) names.insert(info.name);
  });
  return names;
}

TEST(ParticleTable, ResizeGivesEveryArrayOfTheDimensionItsInitialValue) {
  for (const int dimension : {2, 3}) {
    ParticleStore p;
    p.dimension = dimension;
    p.resize(5);
    for_each_particle_member([&](const auto& info, auto member) {
      const auto& v = p.*member;
      ASSERT_EQ(v.size(), info.present_in(dimension) ? 5u : 0u) << info.name << " " << dimension;
      for (const auto& value : v) EXPECT_TRUE(value == info.initial) << info.name;
    });
  }
}

TEST(ParticleTable, NamesAreUnique) {
  std::set<std::string> names;
  for_each_particle_member(
      [&](const auto& info, auto) { EXPECT_TRUE(names.insert(info.name).second) << info.name; });
  EXPECT_EQ(state_names(2).size(), state_arrays(2).size());
  EXPECT_EQ(state_names(3).size(), state_arrays(3).size());
}

// The plane store's arrays, in order, are the ones files and checkpoints
// have always listed; space adds the third component of each vector and
// turns the angle into a quaternion.
TEST(ParticleTable, ThePlaneAndTheSpaceStateRows) {
  std::vector<std::string> plane, space;
  for (const StateArray& a : state_arrays(2)) plane.push_back(a.name);
  for (const StateArray& a : state_arrays(3)) space.push_back(a.name);
  EXPECT_EQ(plane,
            (std::vector<std::string>{"x", "y", "vx", "vy", "theta", "omega", "damping_loss"}));
  EXPECT_EQ(space, (std::vector<std::string>{"x", "y", "z", "vx", "vy", "vz", "qw", "qx", "qy",
                                             "qz", "omega_x", "omega_y", "omega", "damping_loss"}));
}

TEST(ParticleTable, EveryStateArrayOfASpaceStoreGoesThroughASnapshotAndARanksLayout) {
  SolverState s;
  s.particles.dimension = 3;
  s.particles.resize(6);
  for (const ArrayRole role :
       {ArrayRole::state, ArrayRole::reference, ArrayRole::work, ArrayRole::constant})
    fill(s.particles, role);
  const ParticleStore written = s.particles;
  const StateSnapshot snap = StateSnapshot::capture(s);
  ParticleStore fresh;
  fresh.dimension = 3;
  fresh.resize(written.size());
  s.particles = fresh;
  snap.restore(s);
  for_each_particle_member([&](const auto& info, auto member) {
    const auto& expected = info.role == ArrayRole::state ? written.*member : fresh.*member;
    EXPECT_TRUE(same_bits(s.particles.*member, expected)) << info.name;
  });

  LocalLayout layout;
  layout.global_of = {4, 1, 5};
  layout.owned = {0, 2};
  const ParticleStore local = local_particles(written, layout);
  EXPECT_EQ(local.dimension, 3);
  for_each_particle_member([&](const auto& info, auto member) {
    const auto& values = local.*member;
    ASSERT_EQ(values.size(), info.present_in(3) ? 3u : 0u) << info.name;
    for (std::size_t k = 0; k < values.size(); ++k)
      EXPECT_TRUE(values[k] == (written.*member)[layout.global_of[k]]) << info.name;
  });
}

TEST(ParticleTable, EveryStateArrayGoesThroughASnapshot) {
  Simulation sim(testing::rod_case({"l0=0.004"}));
  SolverState& s = sim.state_to_change();
  fill(s.particles, ArrayRole::state);
  const ParticleStore written = s.particles;
  const StateSnapshot snap = StateSnapshot::capture(s);
  ParticleStore fresh;
  fresh.resize(written.size());
  s.particles = fresh;
  snap.restore(s);
  for_each_particle_member([&](const auto& info, auto member) {
    if (info.role == ArrayRole::state)
      EXPECT_TRUE(same_bits(s.particles.*member, written.*member)) << info.name;
    else
      EXPECT_TRUE(same_bits(s.particles.*member, fresh.*member)) << info.name;
  });
}

TEST(ParticleTable, EveryStateArrayGoesThroughACheckpointFile) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("mpsolid_particle_table_" +
       std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".h5");
  Simulation sim(testing::rod_case({"l0=0.004"}));
  fill(sim.state_to_change().particles, ArrayRole::state);
  const ParticleStore written = sim.particles();
  Checkpoint c = capture_state(sim.state());
  c.case_toml = sim.spec().resolved_toml;
  c.bond_hash = sim.state().bonds.hash();
  write_checkpoint(path, c);
  const Checkpoint r = read_checkpoint(path);
  std::filesystem::remove(path);
  std::set<std::string> stored;
  for (const auto& [name, values] : r.particle_arrays) stored.insert(name);
  EXPECT_EQ(stored, state_names());

  Simulation resumed(load_case_text(r.case_toml, path.string()));
  const ParticleStore set_up = resumed.particles();
  restore_state(resumed.state_to_change(), r, path.string());
  for_each_particle_member([&](const auto& info, auto member) {
    const auto& expected = info.role == ArrayRole::state ? written.*member : set_up.*member;
    EXPECT_TRUE(same_bits(resumed.particles().*member, expected)) << info.name;
  });
}

TEST(ParticleTable, EveryArrayGoesThroughARanksPart) {
  Simulation sim(testing::rod_case({"l0=0.004"}));
  SolverState global = sim.state();
  for (const ArrayRole role :
       {ArrayRole::state, ArrayRole::reference, ArrayRole::work, ArrayRole::constant})
    fill(global.particles, role);
  const Decomposition d = decompose_state(global, 2);
  for (int rank = 0; rank < 2; ++rank) {
    const LocalPart sent = local_part(global, d, rank);
    std::vector<std::vector<double>> pieces;
    pack_local_part(sent, [&](const std::vector<double>& piece) { pieces.push_back(piece); });
    std::size_t next = 0;
    const LocalPart got = unpack_local_part([&] { return pieces.at(next++); });
    const LocalLayout& layout = sent.layout;
    EXPECT_EQ(got.state.particles.dimension, 2);
    for_each_particle_member([&](const auto& info, auto member) {
      if (!info.present_in(2)) return;
      const auto& values = got.state.particles.*member;
      ASSERT_EQ(values.size(), layout.size()) << info.name;
      for (std::size_t k = 0; k < layout.size(); ++k)
        ASSERT_TRUE(values[k] == (global.particles.*member)[layout.global_of[k]])
            << info.name << " at local " << k << ", rank " << rank;
    });
  }
}

}  // namespace
}  // namespace mpsolid
