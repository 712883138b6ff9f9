// The paper's rod in space (cases/shock_rod_3d.toml at l0 = 4 mm,
// finite_strain): between frictionless side walls (every particle held in
// z, the plate as deep as the rod) it is the plane case, so its plate
// follows the plane run at the same spacing (cases/shock_rod.toml,
// finite_strain) within 1 % to 10 ms; without them the rod bulges in z, is
// softer, and the plate goes further.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"
#include "tests/support/test_cases.hpp"

namespace mpsolid {
namespace {

struct RodHistory {
  std::vector<double> plate;  // the plate's displacement every 0.25 ms (m)
  double bulge = 0;           // the rod's largest z beyond its start (m)
};

// The plate's x displacement every 0.25 ms to 10 ms (linear between the two
// steps around each instant: the runs' automatic steps differ).
RodHistory push(const std::string& file, const std::vector<std::string>& overrides) {
  std::vector<std::string> all = {"l0=0.004", "model=\"finite_strain\"", "time.dt=\"auto\""};
  all.insert(all.end(), overrides.begin(), overrides.end());
  Simulation sim(load_case(testing::source_path(file), all));
  const bool space = sim.spec().dimension == 3;
  const auto highest = [&] {
    const ParticleStore& p = sim.particles();
    return *std::max_element(p.z.begin() + p.elastic.begin, p.z.begin() + p.elastic.end);
  };
  const double z0 = space ? highest() : 0.0;
  RodHistory out;
  double t_before = 0, x_before = 0;
  for (int k = 1; k <= 40; ++k) {
    const double at = 2.5e-4 * k;
    const auto short_of = static_cast<std::int64_t>((at - sim.time()) / sim.spec().dt) - 1;
    if (short_of > 0) sim.advance(short_of);
    while (sim.time() < at) {
      t_before = sim.time();
      const RigidBody& plate = sim.state().rigid_bodies.at(0);
      x_before = plate.xg - plate.xg0;
      sim.advance(1);
    }
    const RigidBody& plate = sim.state().rigid_bodies.at(0);
    const double x = plate.xg - plate.xg0;
    out.plate.push_back(x_before + (x - x_before) * (at - t_before) / (sim.time() - t_before));
    if (space) out.bulge = std::max(out.bulge, highest() - z0);
  }
  return out;
}

TEST(SpaceRod, BetweenSideWallsItIsThePlaneCaseAndWithoutThemItBulges) {
  const RodHistory plane = push("cases/shock_rod.toml", {});
  const RodHistory walled =
      push("cases/shock_rod_3d.toml", {"bodies.rod.hold=\"z\"", "bodies.plate.z=[-0.02, 0.02]"});
  const RodHistory free = push("cases/shock_rod_3d.toml", {});
  const double largest = *std::max_element(plane.plate.begin(), plane.plate.end());
  EXPECT_GT(largest, 0.01);  // it was pushed (about 15 mm)
  double walled_error = 0;
  for (std::size_t k = 0; k < plane.plate.size(); ++k)
    walled_error = std::max(walled_error, std::abs(walled.plate[k] - plane.plate[k]));
  std::printf(
      "plate: plane %.4f mm at 10 ms; side walls off by %.3f %% of the largest; free "
      "%.4f mm, bulge %.3f mm\n",
      plane.plate.back() * 1e3, 100 * walled_error / largest, free.plate.back() * 1e3,
      free.bulge * 1e3);
  EXPECT_LT(walled_error, 0.01 * largest);  // measured 0.58 %
  EXPECT_EQ(walled.bulge, 0.0);
  EXPECT_GT(free.plate.back(), 1.2 * plane.plate.back());  // softer (measured 1.33 times)
  EXPECT_GT(free.bulge, 0.003);                            // measured 5.0 mm
}

}  // namespace
}  // namespace mpsolid
