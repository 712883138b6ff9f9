// Load histories (src/core/load_history.hpp): each factor against its
// formula, the impulse a varying force gives against the sum of its
// factors, its work closing the energy balance to O(dt), and the input
// checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "src/core/load_history.hpp"
#include "src/core/types.hpp"
#include "src/io/history_writer.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(LoadHistory, FactorsFollowTheirFormulas) {
  LoadHistory step;
  EXPECT_EQ(step.factor(0.0), 1.0);
  EXPECT_EQ(step.factor(5.0), 1.0);

  LoadHistory ramp;
  ramp.kind = LoadHistory::Kind::ramp;
  ramp.rise_time = 2e-6;
  EXPECT_EQ(ramp.factor(0.0), 0.0);
  EXPECT_DOUBLE_EQ(ramp.factor(0.5e-6), 0.25);
  EXPECT_EQ(ramp.factor(2e-6), 1.0);
  EXPECT_EQ(ramp.factor(1.0), 1.0);

  LoadHistory table;
  table.kind = LoadHistory::Kind::table;
  table.times = {1e-6, 2e-6, 4e-6};
  table.factors = {0.5, 1.5, -1.0};
  EXPECT_EQ(table.factor(0.0), 0.5);  // the first before the first time
  EXPECT_EQ(table.factor(1e-6), 0.5);
  EXPECT_DOUBLE_EQ(table.factor(1.5e-6), 1.0);
  EXPECT_NEAR(table.factor(3e-6), 0.25, 1e-15);
  EXPECT_EQ(table.factor(4e-6), -1.0);
  EXPECT_EQ(table.factor(9e-6), -1.0);  // the last after the last

  LoadHistory blast;
  blast.kind = LoadHistory::Kind::friedlander;
  blast.duration = 3e-6;
  blast.decay = 1.2;
  for (const double tau : {0.0, 1e-6, 3e-6, 7e-6})
    EXPECT_DOUBLE_EQ(blast.factor(tau), (1 - tau / 3e-6) * std::exp(-1.2 * tau / 3e-6));
  EXPECT_EQ(blast.factor(0.0), 1.0);
  EXPECT_EQ(blast.factor(3e-6), 0.0);
  EXPECT_LT(blast.factor(4e-6), 0.0);  // the negative phase
}

// The rod case's plate under 11.2 kN times each history.
std::vector<std::vector<std::string>> histories() {
  return {{"loads.shock.history=\"ramp\"", "loads.shock.rise_time=5e-6"},
          {"loads.shock.history=\"table\"",
           "loads.shock.table=[[0.0, 0.0], [2e-6, 1.0], [4e-6, 0.3], [6e-6, 0.8]]"},
          {"loads.shock.history=\"friedlander\"", "loads.shock.duration=6e-6",
           "loads.shock.decay=1.5", "loads.shock.start=1.05e-6"}};
}

TEST(LoadHistory, ImpulseIsTheSumOfTheStepsForces) {
  for (const auto& overrides : histories()) {
    SCOPED_TRACE(overrides[0]);
    const CaseSpec spec = testing::rod_case(overrides);
    Simulation sim(spec);
    const std::int64_t steps = 1000;  // 10 us: the wave is still in the rod
    sim.advance(steps);
    const StepLoad& load = sim.state().loads.at(0);
    double impulse = 0;
    for (std::int64_t k = load.first_step; k < steps; ++k)
      impulse +=
          11200.0 * load.history.factor(static_cast<double>(k) * spec.dt - load.start) * spec.dt;
    const Diagnostics d = sim.diagnostics();
    EXPECT_NEAR(d.momentum_x, impulse, 1e-9 * std::abs(impulse) + 1e-15);
    EXPECT_NEAR(d.momentum_y, 0.0, 1e-9 * std::abs(impulse) + 1e-15);
  }
}

// |KE + SE - W| over the same 20 us at dt and dt / 2: it halves, O(dt).
TEST(LoadHistory, EnergyBalanceClosesToOrderDt) {
  for (const auto& overrides : histories()) {
    SCOPED_TRACE(overrides[0]);
    std::vector<double> imbalance, energy;
    for (const auto& [dt, text] : {std::pair{1e-8, "1e-8"}, std::pair{0.5e-8, "5e-9"}}) {
      std::vector<std::string> o = overrides;
      o.push_back(std::string("time.dt=") + text);
      Simulation sim(testing::rod_case(o));
      sim.advance(static_cast<std::int64_t>(std::llround(2e-5 / dt)));
      const Diagnostics d = sim.diagnostics();
      imbalance.push_back(std::abs(d.kinetic_energy + d.strain_energy - d.external_work));
      energy.push_back(d.kinetic_energy + d.strain_energy);
    }
    // The blast wave's suction phase takes back much of its work: 0.5 % of
    // the energy left at 10 ns, the ramp and the table 0.05 %.
    EXPECT_LT(imbalance[0], 1e-2 * energy[0]);
    const double ratio = imbalance[0] / imbalance[1];
    EXPECT_GT(ratio, 1.6) << imbalance[0] << " then " << imbalance[1];
    EXPECT_LT(ratio, 2.6) << imbalance[0] << " then " << imbalance[1];
  }
}

// history.csv's columns of a varying load: the factor of the step that ran
// last, against the formula, and the load's work (the whole external work
// when it is the only load).
TEST(LoadHistory, HistoryRowsCarryEachVaryingLoadsFactorAndWork) {
  for (const auto& overrides : histories()) {
    SCOPED_TRACE(overrides[0]);
    const CaseSpec spec = testing::rod_case(overrides);
    Simulation sim(spec);
    const std::vector<std::string> cols = history_columns(sim.state(), spec);
    const auto at = std::find(cols.begin(), cols.end(), "load.shock.factor");
    ASSERT_NE(at, cols.end());
    ASSERT_EQ(*(at + 1), "load.shock.work");
    const auto k = static_cast<std::size_t>(at - cols.begin());
    for (const std::int64_t steps : {150, 450, 700}) {
      sim.advance(steps - sim.step());
      const Diagnostics d = sim.diagnostics();
      const std::vector<double> row = history_row(sim.state(), spec, d);
      ASSERT_EQ(row.size(), cols.size());
      const StepLoad& load = sim.state().loads.at(0);
      EXPECT_EQ(row[k], load.history.factor(static_cast<double>(steps - 1) * spec.dt - load.start));
      EXPECT_EQ(row[k + 1], d.external_work);
    }
  }
  // A step load adds no columns: the paper's case writes what it always wrote.
  const CaseSpec step = testing::rod_case();
  Simulation sim(step);
  for (const std::string& c : history_columns(sim.state(), step))
    EXPECT_EQ(c.rfind("load.", 0), std::string::npos) << c;
}

TEST(LoadHistory, BadHistoriesAreRefused) {
  const auto error = [](const std::vector<std::string>& overrides) {
    try {
      testing::rod_case(overrides);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error({"loads.shock.history=\"sine\""}).find("step, ramp, table, friedlander"),
            std::string::npos);
  EXPECT_NE(error({"loads.shock.history=\"ramp\""}).find("loads.shock.rise_time"),
            std::string::npos);
  EXPECT_NE(error({"loads.shock.history=\"ramp\"", "loads.shock.rise_time=0"}).find("(0, inf) s"),
            std::string::npos);
  const std::string unsorted = error({"loads.shock.history=\"table\"",
                                      "loads.shock.table=[[0.0, 0.0], [2e-6, 1.0], [1e-6, 0.3]]"});
  EXPECT_NE(unsorted.find("loads.shock.table"), std::string::npos) << unsorted;
  EXPECT_NE(unsorted.find("point 3"), std::string::npos) << unsorted;
  EXPECT_NE(unsorted.find("increase"), std::string::npos) << unsorted;
  EXPECT_NE(
      error({"loads.shock.history=\"table\"", "loads.shock.table=[[-1e-6, 0.0]]"}).find(">= 0"),
      std::string::npos);
  EXPECT_NE(error({"loads.shock.history=\"table\""}).find("table_file"), std::string::npos);
  EXPECT_NE(error({"loads.shock.history=\"friedlander\"", "loads.shock.duration=1e-6",
                   "loads.shock.decay=-1"})
                .find("loads.shock.decay"),
            std::string::npos);
  EXPECT_NE(error({"loads.shock.rise_time=1e-6"}).find("unknown key"), std::string::npos);
  // A table file: read like the inline table, its bad lines named.

  const std::string good =
      testing::write_temp_file("trace.csv", "t,p\n0,0\n2e-6,1\n4e-6,0.3\n6e-6,0.8\n");
  const CaseSpec from_file = testing::rod_case(
      {"loads.shock.history=\"table\"", "loads.shock.table_file=\"" + good + "\""});
  EXPECT_EQ(from_file.loads.at(0).history, testing::rod_case(histories()[1]).loads.at(0).history);
  const std::string bad = testing::write_temp_file("bad_trace.csv", "t,p\n0,0\n2e-6,one\n");
  const std::string message =
      error({"loads.shock.history=\"table\"", "loads.shock.table_file=\"" + bad + "\""});
  EXPECT_NE(message.find(bad + ":3:"), std::string::npos) << message;
  EXPECT_NE(message.find("loads.shock.table_file"), std::string::npos) << message;
}

}  // namespace
}  // namespace mpsolid
