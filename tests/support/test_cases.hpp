#pragma once
// Cases and comparisons shared by the tests.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "src/solver/case_loader.hpp"
#include "src/solver/simulation.hpp"

namespace mpsolid::testing {

std::string source_path(const std::string& relative);

// The top of a case file: its name and model, l0 = 1 mm, a depth of 1 m and
// a rubber-like material "rubber" (E 2.8 MPa, nu 0.45, rho 1010 kg/m^3);
// the bodies, loads and [time] follow.
std::string rubber_case_head(const std::string& name, const std::string& model);

// Writes `text` to a file called `name` in GoogleTest's temporary folder and
// returns its path.
std::string write_temp_file(const std::string& name, const std::string& text);

// cases/shock_rod.toml with overrides.
CaseSpec rod_case(const std::vector<std::string>& overrides = {});

// A free elastic block of nx x ny particles (l0 = 1 mm, rubber-like material),
// optionally with a rigid plate glued to its left side; no loads, no walls.
CaseSpec free_block_case(int nx, int ny, bool with_rigid_plate, double dt = 1e-7,
                         const std::string& model = "paper");

// Under a homogeneous stress, the particles whose neighbours all have full
// neighbourhoods (4 l0 from every surface of a 12 x 11 free block) feel no
// net force: checks |f| <= tolerance there and returns how many there are.
int expect_interior_force_free(const ParticleStore& p, double l0, double tolerance);

// A fresh model's strain and force passes on the store (a model keeps its own
// per-bond state, so its force pass needs its own strain pass first).
template <class Model>
void run_model_passes(ParticleStore& p, const BondTable& bonds) {
  Model model(p, bonds, {});
  model.compute_strain(p, bonds, p.all());
  model.compute_forces(p, bonds, p.moving());
}

// Moves every moving particle by 5 % of l0 at random (normal, seeded) in x
// and y (and z in space), and in the plane turns it by `angle` plus 5 %
// noise: a deformed, rotated state.
void jiggle(ParticleStore& p, double l0, unsigned seed, double angle);

// A 3D box of nx x ny x nz elastic particles at spacing l0 (its corner at
// the origin, x fastest), of one material, at rest in its reference shape.
ParticleStore space_block(int nx, int ny, int nz, double l0, double lambda, double mu,
                          double density);

// Largest magnitude in v (0 for an empty v).
double max_abs(const std::vector<double>& v);
// Largest magnitude of a 3 x n matrix's entries (a plain loop: GCC 12 warns
// falsely on Eigen's vectorised maxCoeff with AVX-512).
double max_abs(const Eigen::Matrix3Xd& m);

// Every state and work array of two stores is equal bit for bit.
bool same_bits(const ParticleStore& a, const ParticleStore& b);
// Two lists of numbers equal bit for bit.
bool same_bits(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace mpsolid::testing
