#pragma once
// The bond models a case can choose (`model = ...`). Each is a type with the
// same interface (compute_strain, compute_forces, particle_strain_energy,
// check_integrity, uses_rotation); the time step is written once as a
// template over it, and a run dispatches once per call.
#include <string>
#include <variant>
#include <vector>

#include "kernels/finite_strain_model.hpp"
#include "kernels/paper_model.hpp"

namespace mpsolid {

using AnyModel = std::variant<PaperModel, PaperConservativeModel, FiniteStrainModel>;

// The names accepted by `model = ...`, in variant order.
const std::vector<std::string>& model_names();

AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const ModelOptions& options);

}  // namespace mpsolid
