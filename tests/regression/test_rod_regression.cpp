// The paper's case (paper model, 11.2 kN) for 20,000 steps against a stored
// serial reference series: see tests/regression/data/README.md for its
// provenance and the tolerance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "src/io/history_writer.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

struct Table {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

Table read_csv(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << "cannot open " << path;
  Table t;
  std::string line, cell;
  std::getline(in, line);
  std::stringstream header(line);
  while (std::getline(header, cell, ',')) t.columns.push_back(cell);
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::vector<double> row;
    while (std::getline(s, cell, ',')) row.push_back(std::stod(cell));
    t.rows.push_back(row);
  }
  return t;
}

// Relative to each column's largest magnitude: the stored series is
// bit-exact for the build that wrote it; another compiler or libm may round
// sin/cos differently, and those differences grow slowly over 20,000 steps.
constexpr double kTolerance = 1e-8;

void expect_close(const std::vector<std::string>& columns, const std::vector<double>& got,
                  const std::vector<double>& want, const std::vector<double>& scale,
                  const std::string& where) {
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t c = 0; c < got.size(); ++c)
    EXPECT_NEAR(got[c], want[c], kTolerance * scale[c] + 1e-300) << columns[c] << " at " << where;
}

// Columns that are zero but for round-off (the case is symmetric about
// y = 0) are measured against a physical scale made from a companion column,
// since 1e-8 of their own round-off is no tolerance at all: transverse
// momentum against the axial momentum, angular momentum against the axial
// momentum times the rod's length, the plate's transverse displacement
// against its axial one, its rotation against that over its half height.
struct Companion {
  const char* column;
  const char* scale_of;
  double factor;
};
constexpr Companion kCompanions[] = {{"momentum_y", "momentum_x", 1.0},
                                     {"angular_momentum", "momentum_x", 0.1},
                                     {"plate.y", "plate.x", 1.0},
                                     {"plate.theta", "plate.x", 1.0 / 0.03}};

std::vector<double> column_scales(const Table& t) {
  std::vector<double> scale(t.columns.size(), 0.0);
  for (const auto& row : t.rows)
    for (std::size_t c = 0; c < row.size(); ++c) scale[c] = std::max(scale[c], std::abs(row[c]));
  const auto index = [&](const char* name) {
    return static_cast<std::size_t>(std::find(t.columns.begin(), t.columns.end(), name) -
                                    t.columns.begin());
  };
  for (const Companion& c : kCompanions) {
    const std::size_t k = index(c.column), of = index(c.scale_of);
    if (k < scale.size() && of < scale.size()) scale[k] = std::max(scale[k], c.factor * scale[of]);
  }
  return scale;
}

TEST(Regression, PaperRodHistoryMatchesStoredSerialReference) {
  const Table ref =
      read_csv(testing::source_path("tests/regression/data/shock_rod_paper_history.csv"));
  ASSERT_EQ(ref.rows.size(), 11u);
  Simulation sim(testing::rod_case());
  ASSERT_EQ(history_columns(sim.state(), sim.spec()), ref.columns);
  const std::vector<double> scale = column_scales(ref);
  for (std::size_t k = 0; k < ref.rows.size(); ++k) {
    if (k > 0) sim.advance(2000);
    const Diagnostics d = sim.diagnostics();
    expect_close(ref.columns, history_row(sim.state(), sim.spec(), d), ref.rows[k], scale,
                 "step " + std::to_string(sim.step()));
  }
}

TEST(Regression, PaperRodFinalParticlesMatchStoredSerialReference) {
  const Table ref =
      read_csv(testing::source_path("tests/regression/data/shock_rod_paper_particles.csv"));
  Simulation sim(testing::rod_case());
  sim.advance(20000);
  const ParticleStore& p = sim.particles();
  const auto storage = p.storage_of_id();
  ASSERT_EQ(ref.rows.size(), p.size());
  std::vector<double> scale(ref.columns.size(), 0.0);
  for (const auto& row : ref.rows)
    for (std::size_t c = 0; c < row.size(); ++c) scale[c] = std::max(scale[c], std::abs(row[c]));
  for (const auto& row : ref.rows) {
    const std::size_t i = storage.at(static_cast<std::size_t>(row[0]));
    expect_close(ref.columns,
                 {static_cast<double>(p.id[i]), p.x[i], p.y[i], p.vx[i], p.vy[i], p.theta[i]}, row,
                 scale, "id " + std::to_string(p.id[i]));
  }
}

}  // namespace
}  // namespace mpsolid
