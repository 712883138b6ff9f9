#include "kernels/model_registry.hpp"

#include "src/core/types.hpp"

namespace mpsolid {

const std::vector<std::string>& model_names() {
  static const std::vector<std::string> names = {PaperModel::name, PaperConservativeModel::name,
                                                 FiniteStrainModel::name};
  return names;
}

AnyModel make_model(const std::string& name, const ParticleStore& p, const BondTable& bonds,
                    const ModelOptions& options) {
  if (name == PaperModel::name) return PaperModel(p, bonds, options);
  if (name == PaperConservativeModel::name) return PaperConservativeModel(p, bonds, options);
  if (name == FiniteStrainModel::name) return FiniteStrainModel(p, bonds, options);
  throw InputError("unknown model '" + name + "'");
}

}  // namespace mpsolid
