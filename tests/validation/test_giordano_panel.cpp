// The Giordano panel (cases/giordano_panel.toml, docs/gas.md), coarsened to
// 1 mm gas cells and l0 = 0.125 mm and run to 1.45 ms, past the tip's first
// peak: the incident shock's pressure at the top-wall probe against
// Rankine-Hugoniot, the pressure there after the reflection against the
// experiment's 170-185 kPa, and the tip's first peak and its time against
// the experiment (6.2 +- 0.4 mm about 1.3 ms after the shock reaches the
// panel). At this spacing the panel is 4.6 % too flexible in bending (its
// first frequency 2.3 % low: docs/gas.md), which puts the peak 0.4-0.5 mm
// above the converged value; the band asserted is the experiment's widened
// by that much.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "src/gas/shock_relations.hpp"
#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

TEST(GiordanoPanel, TheTipsFirstPeakAndTheWallPressureMatchTheExperiment) {
  Simulation sim(load_case(testing::source_path("cases/giordano_panel.toml"),
                           {"gas.cell=0.001", "l0=0.000125", "time.end=0.00145"}));
  const double arrival = 0.020 / shocked_gas({1.2, 0, 101000}, 1.21, 1.4).shock_speed;
  const double incident = shocked_gas({1.2, 0, 101000}, 1.21, 1.4).behind.p;
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(1e-5 / sim.spec().dt));
  const double tip0 = 0.001;  // the panel's downstream face
  double peak = 0, peak_time = 0, behind_incident = 0, reflected_sum = 0;
  int reflected_rows = 0;
  while (sim.step() < sim.spec().step_count()) {
    sim.advance(std::min(every, sim.spec().step_count() - sim.step()));
    const Diagnostics d = sim.diagnostics();
    const double p = d.gas.probe_p.at(0), t = sim.time();
    // The incident shock passes the probe (10 mm upstream) at about 30 us
    // and the reflection from the panel at about 70 us.
    if (t > 35e-6 && t < 65e-6) behind_incident = std::max(behind_incident, p);
    if (t > 0.4e-3 && t < 1.4e-3) {
      reflected_sum += p;
      ++reflected_rows;
    }
    double xmax = 0;
    const ParticleStore& ps = sim.particles();
    for (std::size_t i = ps.elastic.begin; i < ps.elastic.end; ++i) xmax = std::max(xmax, ps.x[i]);
    const double tip = xmax - (tip0 - 0.5 * sim.spec().l0);
    if (tip > peak) {
      peak = tip;
      peak_time = t;
    }
  }
  const double reflected = reflected_sum / reflected_rows;
  std::printf(
      "Giordano panel (gas cell 1 mm, l0 0.125 mm): tip peak %.3f mm at %.3f ms after the "
      "shock reached the panel; probe %.1f kPa behind the incident shock (exact %.1f), mean "
      "%.1f kPa from 0.4 to 1.4 ms\n",
      1e3 * peak, 1e3 * (peak_time - arrival), 1e-3 * behind_incident, 1e-3 * incident,
      1e-3 * reflected);
  EXPECT_NEAR(behind_incident / incident, 1.0, 0.02);
  EXPECT_GT(reflected, 165e3);
  EXPECT_LT(reflected, 205e3);
  EXPECT_GT(peak, 5.8e-3 - 0.5e-3);
  EXPECT_LT(peak, 6.6e-3 + 0.5e-3);
  EXPECT_NEAR(peak_time - arrival, 1.3e-3, 0.15e-3);
}

}  // namespace
}  // namespace mpsolid
