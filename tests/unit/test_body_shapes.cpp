// Bodies of any shape in a run: the paper's rod with every rectangle written
// as a polygon runs to the same bits, a shaped case with a hole gives the
// same bits at any thread count and reads back from case.resolved.toml, and
// the shipped disk impact rebounds.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>

#include "src/case/resolved_case.hpp"
#include "src/core/parallel.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

std::string shipped_rod_text() {
  std::ifstream in(testing::source_path("cases/shock_rod.toml"));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Each `x = [a, b]` / `y = [c, d]` pair as the polygon of its corners.
std::string as_polygons(const std::string& text, bool clockwise) {
  const std::regex rectangle(R"(x = \[([^,]+), ([^\]]+)\]([^\n]*)\ny = \[([^,]+), ([^\]]+)\])");
  const std::string ccw =
      "shape = \"polygon\"\nvertices = [[$1, $4], [$2, $4], [$2, $5], [$1, $5]]";
  const std::string cw = "shape = \"polygon\"\nvertices = [[$1, $5], [$2, $5], [$2, $4], [$1, $4]]";
  return std::regex_replace(text, rectangle, clockwise ? cw : ccw);
}

TEST(BodyShapes, RectanglesWrittenAsPolygonsRunToTheSameBits) {
  const std::string text = shipped_rod_text();
  // Diagnostics refresh the work arrays, so each run's are read at once.
  const auto run = [](const std::string& toml, const std::string& name) {
    Simulation sim(load_case_text(toml, name, {"l0=0.001"}));
    sim.advance(2000);
    return std::pair{sim.diagnostics(), sim.particles()};
  };
  const auto [reference, rectangles] = run(text, "shock_rod.toml");
  for (const bool clockwise : {false, true}) {
    const std::string polygons = as_polygons(text, clockwise);
    std::size_t written = 0;
    for (std::size_t at = polygons.find("shape = \"polygon\""); at != std::string::npos;
         at = polygons.find("shape = \"polygon\"", at + 1))
      ++written;
    ASSERT_EQ(written, 3u) << polygons;
    const auto [diagnostics, particles] = run(polygons, "shock_rod_polygons.toml");
    EXPECT_TRUE(testing::same_bits(particles, rectangles)) << "clockwise " << clockwise;
    EXPECT_EQ(diagnostics.kinetic_energy, reference.kinetic_energy);
    EXPECT_EQ(diagnostics.external_work, reference.external_work);
  }
}

// A rubber disk with an off-centre hole, spinning and moving, and a turned
// rigid bar beside it.
std::string shaped_case() {
  return testing::rubber_case_head("shaped", "paper") + R"(
[bodies.disk]
kind = "elastic"
material = "rubber"
shape = "circle"
center = [0.0, 0.0]
radius = 0.012
holes = [{ shape = "ellipse", center = [0.003, 0.001], semi_axes = [0.004, 0.002], angle = 20 }]
velocity = [1.0, 0.0]
spin = 20.0

[bodies.bar]
kind = "rigid"
material = "rubber"
x = [0.02, 0.05]
y = [-0.004, 0.004]
angle = 30
velocity = [-1.0, 0.0]

[time]
dt = 1.0e-7
end = 1.0e-4
)";
}

TEST(BodyShapes, ShapedCaseIsBitIdenticalAt1To3Threads) {
  const CaseSpec spec = load_case_text(shaped_case(), "shaped.toml", {});
  set_thread_count(1);
  Simulation one(spec);
  one.advance(300);
  for (const int threads : {2, 3}) {
    set_thread_count(threads);
    Simulation many(spec);
    many.advance(300);
    EXPECT_TRUE(testing::same_bits(one.particles(), many.particles())) << threads << " threads";
  }
  set_thread_count(available_cores());
}

TEST(BodyShapes, ResolvedCaseReadsBackToTheSameParticles) {
  const CaseSpec spec = load_case_text(shaped_case(), "shaped.toml", {});
  const std::string resolved = resolved_case_toml(spec);
  EXPECT_NE(resolved.find("shape = \"circle\""), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("holes = ["), std::string::npos) << resolved;
  const CaseSpec again = load_case_text(resolved, "shaped.toml", {});
  EXPECT_EQ(resolved_case_toml(again), resolved);
  Simulation a(spec), b(again);
  EXPECT_TRUE(testing::same_bits(a.particles(), b.particles()));
  EXPECT_GT(a.particles().size(), 300u);
}

// cases/disk_impact.toml: the disk flattens against the wall and rebounds,
// its energy kept (vibration takes the rest of the approach's), the same
// bits at 1 and 2 threads.
TEST(BodyShapes, DiskThrownAtAWallRebounds) {
  const CaseSpec spec = load_case(testing::source_path("cases/disk_impact.toml"));
  std::vector<ParticleStore> ends;
  for (const int threads : {1, 2}) {
    set_thread_count(threads);
    Simulation sim(spec);
    const Diagnostics start = sim.diagnostics();
    sim.advance(sim.spec().step_count());  // dt = "auto": chosen by the Simulation
    const Diagnostics end = sim.diagnostics();
    ends.push_back(sim.particles());
    EXPECT_LT(start.momentum_x, 0.0);
    EXPECT_GT(end.momentum_x, 0.5 * -start.momentum_x);  // rebounding
    EXPECT_LT(end.momentum_x, -start.momentum_x);
    EXPECT_EQ(end.contact_energy, 0.0);  // away from the wall again
    const double e0 = start.kinetic_energy, e1 = end.kinetic_energy + end.strain_energy;
    EXPECT_NEAR(e1, e0, 0.01 * e0);
  }
  EXPECT_TRUE(testing::same_bits(ends[0], ends[1]));
  set_thread_count(available_cores());
}

}  // namespace
}  // namespace mpsolid
