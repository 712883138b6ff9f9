#include "tests/support/test_cases.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <random>

#include <cmath>
#include <cstdio>
#include <cstring>

namespace mpsolid::testing {

std::string source_path(const std::string& relative) {
  return std::string(MPSOLID_SOURCE_DIR) + "/" + relative;
}

std::string rubber_case_head(const std::string& name, const std::string& model) {
  return "name = \"" + name + "\"\nmodel = \"" + model +
         "\"\nl0 = 0.001\ndepth = 1.0\n\n[materials.rubber]\nE = 2.8e6\nnu = 0.45\nrho = 1010.0\n";
}

std::string write_temp_file(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(text.c_str(), f);
  std::fclose(f);
  return path;
}

CaseSpec rod_case(const std::vector<std::string>& overrides) {
  return load_case(source_path("cases/shock_rod.toml"), overrides);
}

CaseSpec free_block_case(int nx, int ny, bool with_rigid_plate, double dt,
                         const std::string& model) {
  const double l0 = 1e-3;
  std::string text = fmt::format(R"(
l0 = {l0}
[materials.rubber]
E = 2.8e6
nu = 0.45
rho = 1010.0
[bodies.block]
kind = "elastic"
material = "rubber"
x = [0.0, {x1}]
y = [0.0, {y1}]
[time]
dt = {dt}
end = {dt}
)",
                                 fmt::arg("l0", l0), fmt::arg("x1", nx * l0),
                                 fmt::arg("y1", ny * l0), fmt::arg("dt", dt));
  if (with_rigid_plate)
    text += fmt::format(R"(
[bodies.plate]
kind = "rigid"
material = "rubber"
x = [{x0}, 0.0]
y = [{y0}, {y1}]
)",
                        fmt::arg("x0", -3 * l0), fmt::arg("y0", -2 * l0),
                        fmt::arg("y1", (ny + 2) * l0));
  return load_case_text(text, "free_block.toml", {"model=" + model});
}

int expect_interior_force_free(const ParticleStore& p, double l0, double tolerance) {
  int interior = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.x0[i] > 4 * l0 && p.x0[i] < 8 * l0 && p.y0[i] > 4 * l0 && p.y0[i] < 7 * l0) {
      ++interior;
      EXPECT_NEAR(p.fx[i], 0.0, tolerance) << "particle " << p.id[i];
      EXPECT_NEAR(p.fy[i], 0.0, tolerance) << "particle " << p.id[i];
    }
  return interior;
}

void jiggle(ParticleStore& p, double l0, unsigned seed, double angle) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  for (std::size_t i = p.moving().begin; i < p.size(); ++i) {
    p.x[i] += 0.05 * l0 * n(rng);
    p.y[i] += 0.05 * l0 * n(rng);
    if (p.dimension == 3)
      p.z[i] += 0.05 * l0 * n(rng);
    else
      p.theta[i] = angle + 0.05 * n(rng);
  }
}

ParticleStore space_block(int nx, int ny, int nz, double l0, double lambda, double mu,
                          double density) {
  ParticleStore p;
  p.dimension = 3;
  p.resize(static_cast<std::size_t>(nx * ny * nz));
  std::size_t i = 0;
  for (int c = 0; c < nz; ++c)
    for (int b = 0; b < ny; ++b)
      for (int a = 0; a < nx; ++a, ++i) {
        p.x[i] = p.x0[i] = (a + 0.5) * l0;
        p.y[i] = p.y0[i] = (b + 0.5) * l0;
        p.z[i] = p.z0[i] = (c + 0.5) * l0;
        p.id[i] = static_cast<std::int32_t>(i);
        p.lambda[i] = lambda;
        p.mu[i] = mu;
        p.inv_mass[i] = 1.0 / (density * l0 * l0 * l0);
      }
  p.set_kind_ranges();
  return p;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

double max_abs(const Eigen::Matrix3Xd& m) {
  double out = 0;
  for (Eigen::Index c = 0; c < m.cols(); ++c)
    for (int r = 0; r < 3; ++r) out = std::max(out, std::abs(m(r, c)));
  return out;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

bool same_bits(const ParticleStore& a, const ParticleStore& b) {
  bool same = true;
  for_each_particle_member([&](const auto& info, auto member) {
    const auto &u = a.*member, &v = b.*member;
    if (info.role == ArrayRole::state || info.role == ArrayRole::work)
      same = same && u.size() == v.size() &&
             (u.empty() || std::memcmp(u.data(), v.data(), u.size() * sizeof(u[0])) == 0);
  });
  return same;
}

}  // namespace mpsolid::testing
