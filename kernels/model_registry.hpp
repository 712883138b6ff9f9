#pragma once
// The bond models a case can choose (`model = ...`): one line each in
// AnyModel. The time step is written once as a template over the model
// (kernels/model_concept.hpp), and a run dispatches once per call.
#include <string>
#include <variant>
#include <vector>

#include "kernels/finite_strain_model.hpp"
#include "kernels/gradient_gather_model.hpp"
#include "kernels/linear_elastic_model.hpp"
#include "kernels/model_concept.hpp"
#include "kernels/paper_gather_model.hpp"
#include "kernels/paper_model.hpp"

namespace mpsolid {

// Each model twice: its plane kernels, then its kernels in space (the same
// name and options; MODEL.md section 10). make_model picks by the store's
// dimension.
using AnyModel =
    std::variant<PaperModel, PaperConservativeModel, FiniteStrainModel, LinearElasticModel,
                 PaperGatherModel<false>, PaperGatherModel<true>,
                 GradientGatherModel<3, NeoHookeanLaw>, GradientGatherModel<3, HookeLaw>>;
// The plane alternatives come first: the catalog's models.
inline constexpr std::size_t kModelCount = 4;

// Every model's name, case section and options table, in variant order.
const std::vector<ModelInfo>& model_catalog();
// Their names, in the same order.
std::vector<std::string> model_names();
// The catalog entry of `name` (throws InputError for an unknown name).
const ModelInfo& model_info(const std::string& name);

// The model called `name` for the store's dimension, its coefficients made
// for `bonds`; `options` are
// its validated section (CaseSpec::model_options). Particles outside
// `whole_rows` hold only part of their bond row (a rank's ghosts,
// docs/mpi.md): what the model derives from whole rows is left for the halo.
AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const OptionValues& options);
AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const OptionValues& options, Range whole_rows);

}  // namespace mpsolid
