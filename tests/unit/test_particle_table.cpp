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

std::set<std::string> state_names() {
  std::set<std::string> names;
  for_each_particle_member([&](const auto& info, auto) {
    if (info.role == ArrayRole::state) names.insert(info.name);
  });
  return names;
}

TEST(ParticleTable, ResizeGivesEveryArrayItsInitialValue) {
  ParticleStore p;
  p.resize(5);
  for_each_particle_array(p, [&](const auto& info, const auto& v) {
    ASSERT_EQ(v.size(), 5u) << info.name;
    for (const auto& value : v) EXPECT_TRUE(value == info.initial) << info.name;
  });
}

TEST(ParticleTable, NamesAreUnique) {
  std::set<std::string> names;
  for_each_particle_member(
      [&](const auto& info, auto) { EXPECT_TRUE(names.insert(info.name).second) << info.name; });
  EXPECT_EQ(state_names().size(), kStateArrays.size());
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
    for_each_particle_member([&](const auto& info, auto member) {
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
